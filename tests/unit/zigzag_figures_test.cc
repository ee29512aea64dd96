// Zigzag figures (IMO MSC.137(76)) on hand-built heading traces with known overshoots, check
// times and period, and records that are not zigzags.
#include "engine/data/zigzag_figures.h"

#include <cmath>
#include <utility>
#include <vector>

#include "gtest/gtest.h"

namespace vesselid {
namespace zigzag_figures_test {

constexpr double kDegree = M_PI / 180.0;

// Piecewise-linear through the knots (t, value).
double Through(const std::vector<std::pair<double, double>>& knots, double t) {
  if (t <= knots.front().first) return knots.front().second;
  for (size_t k = 1; k < knots.size(); ++k) {
    if (t <= knots[k].first) {
      const auto [t0, v0] = knots[k - 1];
      const auto [t1, v1] = knots[k];
      return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
    }
  }
  return knots.back().second;
}

// A 10/10 zigzag: rudder 10 deg at t = 1, reversed at 11, 25, 41 and 55 s where the heading
// change reaches +-10 deg; heading peaks 14, -16, 13, -15 deg (overshoots 4, 6, 3, 5 deg).
// `side` -1 flies it to port first; `offset` is the base course.
struct Trace {
  std::vector<double> t, delta, psi;
};

Trace TenTen(double side = 1.0, double offset = 0.0) {
  const std::vector<std::pair<double, double>> heading = {{0, 0},    {1, 0},    {11, 10}, {13, 14},
                                                          {25, -10}, {28, -16}, {41, 10}, {43, 13},
                                                          {55, -10}, {57, -15}, {70, 5}};
  const double switches[] = {1, 11, 25, 41, 55};
  Trace trace;
  for (int k = 0; k <= 700; ++k) {
    const double t = 0.1 * k;
    int executed = 0;
    for (double s : switches) executed += t >= s - 1e-9 ? 1 : 0;
    const double rudder = executed == 0 ? 0.0 : (executed % 2 == 1 ? 10.0 : -10.0);
    trace.t.push_back(t);
    trace.delta.push_back(side * rudder * kDegree);
    trace.psi.push_back(offset + side * Through(heading, t) * kDegree);
  }
  return trace;
}

TEST(ZigzagFigures, KnownOvershootsCheckTimeAndPeriod) {
  for (double side : {1.0, -1.0}) {
    const Trace trace = TenTen(side, 2.0);
    ZigzagTest test;
    std::string why;
    ASSERT_TRUE(DetectZigzag(trace.t, trace.delta, trace.psi, &test, &why)) << why;
    EXPECT_NEAR(test.rudder / kDegree, 10.0, 1e-9);
    // The median heading change at the last samples before the reversals (9.9, 9.8, 9.8, 9.81).
    EXPECT_NEAR(test.heading / kDegree, 9.804, 1e-3);
    EXPECT_NEAR(test.first_execute, 0.9, 1e-9);  // the last sample before the rudder moves
    EXPECT_EQ(test.sign, side);
    EXPECT_EQ(test.reversals, 4);
    test.heading = 10.0 * kDegree;  // the nominal check angle
    test.first_execute = 1.0;
    const ZigzagFigures f = MeasureZigzag(trace.t, trace.psi, test);
    EXPECT_NEAR(f.first_overshoot / kDegree, 4.0, 1e-6);
    EXPECT_NEAR(f.second_overshoot / kDegree, 6.0, 1e-6);
    EXPECT_NEAR(f.time_to_first_check, 10.0, 0.11);
    ASSERT_EQ(f.executes.size(), 5u);  // t_0 and four checks
    // (25 - 1 + 41 - 11 + 55 - 25) / 3
    EXPECT_NEAR(f.period, 28.0, 0.11);
  }
}

// A record that ends before the heading turns back has no second overshoot.
TEST(ZigzagFigures, OvershootNeedsTheHeadingToTurnBack) {
  Trace trace = TenTen();
  const size_t keep = 270;  // up to t = 26.9 s, the heading still falling past -10 deg
  trace.t.resize(keep);
  trace.psi.resize(keep);
  ZigzagTest test;
  test.heading = 10.0 * kDegree;
  test.first_execute = 1.0;
  const ZigzagFigures f = MeasureZigzag(trace.t, trace.psi, test);
  EXPECT_NEAR(f.first_overshoot / kDegree, 4.0, 1e-6);
  EXPECT_TRUE(std::isnan(f.second_overshoot));
  EXPECT_NEAR(f.period, 24.0, 0.11);
}

// A sine-swept rudder, and a zigzag whose reversals do not follow the heading, are not
// zigzag tests.
TEST(ZigzagFigures, OtherManoeuvresAreNotZigzags) {
  Trace sine;
  for (int k = 0; k <= 2000; ++k) {
    const double t = 0.1 * k;
    sine.t.push_back(t);
    sine.delta.push_back(0.2 * std::sin(0.2 * t));
    sine.psi.push_back(-0.3 * std::cos(0.2 * t));
  }
  ZigzagTest test;
  std::string why;
  EXPECT_FALSE(DetectZigzag(sine.t, sine.delta, sine.psi, &test, &why));
  EXPECT_EQ(why, "the rudder is not held");

  Trace timed = TenTen();
  for (size_t i = 0; i < timed.t.size(); ++i) timed.psi[i] = 0.002 * timed.t[i];  // a drift
  EXPECT_FALSE(DetectZigzag(timed.t, timed.delta, timed.psi, &test, &why));
  EXPECT_EQ(why, "the rudder reversals do not follow the heading checks");
}

}  // namespace zigzag_figures_test
}  // namespace vesselid
