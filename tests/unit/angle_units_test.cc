// Degrees read as radians (angle_units.h) and the fit of a wrapped angle (metrics.h): the check
// on headings logged in degrees by a zigzag and across the 0/360 wrap, and its silence on
// radian logs that wrap, turn many times one way, or zigzag; the fit % of a wrapped channel
// measured against its spread modulo one turn.
#include "engine/data/angle_units.h"

#include <cmath>
#include <random>
#include <vector>

#include "engine/base/angle.h"
#include "engine/solve/metrics.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace angle_units_test {

constexpr double kDeg = 180.0 / M_PI;

// A zigzag heading: +-amplitude [rad] around `mean`, period 60 s, sampled at 10 Hz with noise.
std::vector<double> Zigzag(double mean, double amplitude, double seconds, double noise) {
  std::mt19937 random(7);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<double> psi;
  for (double t = 0; t < seconds; t += 0.1) {
    psi.push_back(mean + amplitude * std::sin(2 * M_PI * t / 60.0) + n(random));
  }
  return psi;
}

TEST(AngleUnitTest, ZigzagInDegreesLooksLikeDegrees) {
  std::vector<double> psi = Zigzag(0.3, 0.35, 300, 0.002);  // +-20 deg
  for (double& v : psi) v *= kDeg;
  const AngleUnitCheck check = CheckAngleUnit(psi);
  EXPECT_TRUE(check.looks_like_degrees);
  EXPECT_GT(check.max - check.min, 2 * M_PI);
  EXPECT_NE(DescribeDegreesLook("psi", check).find("column 'psi' looks like degrees: range "),
            std::string::npos);
}

TEST(AngleUnitTest, CompassHeadingInDegreesAcrossNorthLooksLikeDegrees) {
  // A steady turn logged as a compass heading in [0, 360): wraps from 359.x to 0.x.
  std::vector<double> psi;
  for (double t = 0; t < 200; t += 1.0) psi.push_back(std::fmod(300.0 + 0.8 * t, 360.0));
  const AngleUnitCheck check = CheckAngleUnit(psi);
  EXPECT_TRUE(check.looks_like_degrees);
  EXPECT_GT(check.largest_step, 300.0);
}

TEST(AngleUnitTest, RadianLogsDoNotLookLikeDegrees) {
  // A zigzag in radians, with missing samples.
  std::vector<double> zigzag = Zigzag(0.3, 0.35, 300, 0.002);
  zigzag[10] = std::nan("");
  EXPECT_FALSE(CheckAngleUnit(zigzag).looks_like_degrees);
  // Many turns one way, logged unwrapped (range 40 rad) and wrapped to (-pi, pi].
  std::vector<double> unwrapped, wrapped;
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (double t = 0; t < 400; t += 0.1) {
    unwrapped.push_back(0.1 * t + noise(random));
    wrapped.push_back(WrapAngle(unwrapped.back()));
  }
  EXPECT_FALSE(CheckAngleUnit(unwrapped).looks_like_degrees);
  EXPECT_FALSE(CheckAngleUnit(wrapped).looks_like_degrees);
  // A spiral test in radians: five turns one way, then two and a half back (range 31 rad,
  // travel 47 rad above 1.5 x the range, one reversal).
  std::vector<double> spiral;
  for (double t = 0; t < 300; t += 0.1) spiral.push_back(0.1025 * t + noise(random));
  for (double t = 0; t < 150; t += 0.1) spiral.push_back(30.75 - 0.1025 * t + noise(random));
  EXPECT_FALSE(CheckAngleUnit(spiral).looks_like_degrees);
  // A zigzag around south logged in (-pi, pi]: jumps of 2 pi at the wrap.
  std::vector<double> south = Zigzag(M_PI, 0.3, 300, 0.002);
  for (double& v : south) v = WrapAngle(v);
  EXPECT_FALSE(CheckAngleUnit(south).looks_like_degrees);
}

// A wrapped heading whose measurement spans many turns (degrees read as radians) and a
// simulation that misses it by a uniform angle: the wrapped residual stays below pi, yet the
// fit must not look good. The old spread about the plain mean (20 rad) made it ~90 %.
TEST(WrappedFitTest, SpreadIsTakenModuloOneTurn) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> miss(-M_PI, M_PI);
  const std::vector<double> measured = Zigzag(0.0, 0.35 * kDeg, 300, 0.1);
  MetricAccumulator wrapped;
  for (double y : measured) wrapped.Add(y + miss(random), y, true);
  const ChannelMetrics m = wrapped.Finish("zz", "psi");
  EXPECT_LT(m.fit_percent, 20.0) << m.fit_percent;
  EXPECT_LT(m.r2, 0.3) << m.r2;

  // A good simulation of a heading wrapped around south still fits well: the spread is taken
  // about the circular mean, not inflated by the wrap.
  std::normal_distribution<double> small(0.0, 0.01);
  MetricAccumulator south;
  for (double y : Zigzag(M_PI, 0.3, 300, 0.0)) {
    south.Add(WrapAngle(y + small(random)), WrapAngle(y), true);
  }
  const ChannelMetrics s = south.Finish("zz", "psi");
  EXPECT_GT(s.fit_percent, 90.0) << s.fit_percent;
  EXPECT_LT(s.fit_percent, 99.5) << s.fit_percent;  // spread 0.3 rad, not ~pi from the wrap
}

}  // namespace angle_units_test
}  // namespace vesselid
