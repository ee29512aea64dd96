// The glitch screen (glitch_screen.h) on a track no model made: a vessel on a circle of
// 40 m radius at 2 m/s, GNSS noise 0.3 m at 10 Hz with +-30 ms row jitter, heading in degrees
// wrapping through 360, with each kind of defect put in at known rows.
#include "engine/data/glitch_screen.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace glitch_screen_test {

constexpr int kRows = 600;

Trajectory Track(unsigned seed = 7) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Trajectory data;
  data.names = {"north", "east", "heading", "rpm"};
  data.columns.assign(4, {});
  for (int k = 0; k < kRows; ++k) {
    const double t = 0.1 * k + jitter(random);
    const double angle = 2.0 * t / 40.0;  // rad
    data.t.push_back(t);
    data.columns[0].push_back(40.0 * std::sin(angle) + noise(random));
    data.columns[1].push_back(40.0 * (1.0 - std::cos(angle)) + noise(random));
    data.columns[2].push_back(std::fmod(angle * 180.0 / M_PI + 350.0, 360.0) + 0.2 * noise(random));
    data.columns[3].push_back(1200.0);
  }
  return data;
}

GlitchScreenOptions Options() {
  GlitchScreenOptions o;
  o.north_column = "north";
  o.east_column = "east";
  o.max_speed = 5.0;
  o.channels = {{"heading", 30.0, 360.0}};
  o.stale = 4;
  return o;
}

int Missing(const Trajectory& data, int column) {
  int n = 0;
  for (double v : data.columns[column]) n += std::isnan(v);
  return n;
}

TEST(GlitchScreen, CleanTrackPassesUntouched) {
  Trajectory data = Track();
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  EXPECT_TRUE(findings.empty()) << DescribeGlitches(findings);
  EXPECT_EQ(Missing(data, 0) + Missing(data, 2), 0);
}

TEST(GlitchScreen, ZeroFix) {
  Trajectory data = Track();
  data.columns[0][100] = data.columns[1][100] = 0.0;
  data.columns[0][0] = 0.0;  // one coordinate at 0 alone is a position like any other
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  ASSERT_EQ(findings.size(), 1u) << DescribeGlitches(findings);
  EXPECT_EQ(findings[0].kind, "zero fix");
  EXPECT_EQ(findings[0].first_times, std::vector<double>{data.t[100]});
  EXPECT_TRUE(std::isnan(data.columns[0][100]) && std::isnan(data.columns[1][100]));
  EXPECT_EQ(Missing(data, 0), 1);
}

TEST(GlitchScreen, PositionJumpsAndHeadingSpikes) {
  Trajectory data = Track();
  data.columns[0][200] += 15.0;  // one fix 15 m off
  data.columns[0][300] += 8.0;   // two fixes 8 m off together
  data.columns[1][301] += 8.0;
  data.columns[0][301] += 8.0;
  data.columns[2][400] = std::fmod(data.columns[2][400] + 90.0, 360.0);  // heading spike
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  ASSERT_EQ(findings.size(), 2u) << DescribeGlitches(findings);
  EXPECT_EQ(findings[0].kind, "jump");
  EXPECT_EQ(findings[0].channel, "north/east");
  EXPECT_EQ(findings[0].count, 3);
  EXPECT_EQ(findings[0].first_times, (std::vector<double>{data.t[200], data.t[300], data.t[301]}));
  EXPECT_EQ(findings[1].channel, "heading");
  EXPECT_EQ(findings[1].count, 1);
  EXPECT_EQ(Missing(data, 0), 3);
  EXPECT_EQ(Missing(data, 2), 1);
  // The heading wraps through 360 on this track (350 deg + one turn) without a jump.
  EXPECT_NE(DescribeGlitches(findings).find("3 jump(s) faster than the screen's bound in "
                                            "north/east (t = "),
            std::string::npos);
}

TEST(GlitchScreen, StaleRepeatsWhileOthersChange) {
  Trajectory data = Track();
  for (int k = 151; k < 157; ++k) {  // the fix of row 150 repeated 6 more times
    data.columns[0][k] = data.columns[0][150];
    data.columns[1][k] = data.columns[1][150];
  }
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  ASSERT_GE(findings.size(), 1u);
  EXPECT_EQ(findings[0].kind, "stale repeat");
  EXPECT_EQ(findings[0].count, 6);
  EXPECT_EQ(findings[0].first_times.front(), data.t[151]);
  EXPECT_FALSE(std::isnan(data.columns[0][150]));
  // The fix after the stale run is 0.7 s of travel away: no jump.
  EXPECT_EQ(findings.size(), 1u) << DescribeGlitches(findings);
  // A constant channel (rpm) is not screened and is never stale on its own: with every
  // screened channel frozen, nothing changes and nothing is removed.
  Trajectory still = Track();
  for (int k = 0; k < kRows; ++k) {
    still.columns[0][k] = 1.0;
    still.columns[1][k] = 2.0;
    still.columns[2][k] = 10.0;
  }
  EXPECT_TRUE(ScreenGlitches(Options(), &still).empty());
}

// A log of one screened output (the heading) has no other output to tell a held value from a
// still vessel: a mapped input that moves (reference column) does. A reference that does not
// move marks nothing, and with two screened channels the references are not used.
TEST(GlitchScreen, StaleRepeatsOfASingleOutputAgainstTheInputs) {
  Trajectory data = Track();
  data.names.push_back("rudder");
  data.columns.emplace_back();
  for (int k = 0; k < kRows; ++k) data.columns[4].push_back(0.2 * std::sin(0.05 * k));
  for (int k = 301; k < 306; ++k) data.columns[2][k] = data.columns[2][300];
  GlitchScreenOptions options;
  options.channels = {{"heading", 0.0, 360.0}};
  options.stale = 4;
  Trajectory held = data;
  EXPECT_TRUE(ScreenGlitches(options, &held).empty());  // no reference: nothing to compare
  options.reference_columns = {"rpm"};  // constant
  EXPECT_TRUE(ScreenGlitches(options, &held).empty());
  options.reference_columns = {"rpm", "rudder"};
  const std::vector<GlitchFinding> findings = ScreenGlitches(options, &held);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].kind, "stale repeat");
  EXPECT_EQ(findings[0].count, 5);
  EXPECT_EQ(Missing(held, 4), 0);  // a reference is never screened
}

TEST(GlitchScreen, LastingMoveIsKeptAsTheTrack) {
  Trajectory data = Track();
  for (int k = 350; k < kRows; ++k) data.columns[0][k] += 30.0;  // a relocated antenna
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  ASSERT_EQ(findings.size(), 1u) << DescribeGlitches(findings);
  EXPECT_EQ(findings[0].kind, "re-anchored");
  EXPECT_EQ(findings[0].first_times.front(), data.t[350]);
  EXPECT_EQ(Missing(data, 0), 0);  // five consistent samples prove the move: all kept
  EXPECT_NE(DescribeGlitches(findings).find("1 lasting move(s) kept as the track"),
            std::string::npos);
}

// A logger's bad first row (a heading 150 deg off, 3 s before the next row) and a bad last
// row: each is a jump removed like any other glitch, not the anchor the rest of the record is
// judged from.
TEST(GlitchScreen, BadFirstAndLastRowsAreGlitches) {
  Trajectory data = Track();
  data.t[0] = data.t[1] - 3.0;
  data.columns[2][0] = std::fmod(data.columns[2][1] + 150.0, 360.0);
  data.columns[2][kRows - 1] = std::fmod(data.columns[2][kRows - 1] + 180.0, 360.0);
  const std::vector<GlitchFinding> findings = ScreenGlitches(Options(), &data);
  ASSERT_EQ(findings.size(), 1u) << DescribeGlitches(findings);
  EXPECT_EQ(findings[0].kind, "jump");
  EXPECT_EQ(findings[0].count, 2);
  EXPECT_TRUE(std::isnan(data.columns[2][0]));
  EXPECT_TRUE(std::isnan(data.columns[2][kRows - 1]));
  EXPECT_EQ(Missing(data, 2), 2);
}

}  // namespace glitch_screen_test
}  // namespace vesselid
