// Turning circle figures (IMO MSC.137(76)) on hand-built tracks with known advance, transfer
// and tactical diameter, and records that are not turning circles.
#include "engine/data/turning_figures.h"

#include <cmath>
#include <vector>

#include "gtest/gtest.h"

namespace vesselid {
namespace turning_figures_test {

constexpr double kDegree = M_PI / 180.0;

struct Track {
  std::vector<double> t, delta, x, y, psi;
};

// Straight at speed V on course `course` until t = 5 s, where the rudder goes to `side` x 35
// deg and the ship turns at once on a circle of radius R (rate V/R): advance = transfer = R,
// tactical diameter 2 R, 90 deg after pi R / (2 V) s.
Track Circle(double side, double course, double radius = 20.0, double speed = 1.0) {
  Track track;
  double x = 3.0, y = -2.0, psi = course;
  const double dt = 0.01;
  for (int k = 0; k <= 20000; ++k) {
    const double t = k * dt;
    track.t.push_back(t);
    track.delta.push_back(t >= 5.0 ? side * 35 * kDegree : 0.0);
    track.x.push_back(x);
    track.y.push_back(y);
    track.psi.push_back(psi);
    const double rate = t >= 5.0 ? side * speed / radius : 0.0;
    // Exact arc over the step.
    if (rate == 0.0) {
      x += speed * std::cos(psi) * dt;
      y += speed * std::sin(psi) * dt;
    } else {
      const double next = psi + rate * dt;
      x += speed / rate * (std::sin(next) - std::sin(psi));
      y += speed / rate * (-std::cos(next) + std::cos(psi));
      psi = next;
    }
  }
  return track;
}

TEST(TurningFigures, CircleFiguresAreItsRadiusAndDiameter) {
  for (double side : {1.0, -1.0}) {
    for (double course : {0.0, 1.0, -2.5}) {
      const Track c = Circle(side, course);
      TurningTest test;
      std::string why;
      ASSERT_TRUE(DetectTurningCircle(c.t, c.delta, c.psi, &test, &why)) << why;
      EXPECT_NEAR(test.execute, 5.0, 0.011);
      EXPECT_EQ(test.sign, side);
      EXPECT_NEAR(test.rudder, side * 35 * kDegree, 1e-12);
      const TurningFigures f = MeasureTurningCircle(c.t, c.x, c.y, c.psi, test);
      EXPECT_NEAR(f.advance, 20.0, 1e-3) << side << " " << course;
      EXPECT_NEAR(f.transfer, 20.0, 1e-3);
      EXPECT_NEAR(f.tactical_diameter, 40.0, 1e-3);
      EXPECT_NEAR(f.time_to_90, M_PI * 10.0, 0.02);
      EXPECT_NEAR(f.time_to_180, M_PI * 20.0, 0.02);
    }
  }
}

TEST(TurningFigures, FigureUnknownWhereTheRecordEndsFirst) {
  Track c = Circle(1.0, 0.0);
  const size_t end = 5000;  // 50 s: 90 deg at 36.4 s, 180 deg at 67.8 s
  for (auto* column : {&c.t, &c.delta, &c.x, &c.y, &c.psi}) column->resize(end);
  TurningTest test;
  ASSERT_TRUE(DetectTurningCircle(c.t, c.delta, c.psi, &test));
  const TurningFigures f = MeasureTurningCircle(c.t, c.x, c.y, c.psi, test);
  EXPECT_NEAR(f.advance, 20.0, 1e-3);
  EXPECT_TRUE(std::isnan(f.tactical_diameter));
  EXPECT_TRUE(std::isnan(f.time_to_180));
}

TEST(TurningFigures, NotATurningCircle) {
  TurningTest test;
  std::string why;
  // The rudder reversed halfway: a zigzag's rudder, not a held one.
  Track c = Circle(1.0, 0.0);
  for (size_t k = 10000; k < c.delta.size(); ++k) c.delta[k] = -c.delta[k];
  EXPECT_FALSE(DetectTurningCircle(c.t, c.delta, c.psi, &test, &why));
  EXPECT_EQ(why, "the rudder is not held");
  // A small course change: 3 deg of rudder.
  c = Circle(1.0, 0.0);
  for (double& d : c.delta) d *= 3.0 / 35.0;
  EXPECT_FALSE(DetectTurningCircle(c.t, c.delta, c.psi, &test, &why));
  EXPECT_EQ(why, "the rudder moves less than 5 deg");
  // The heading turns only 45 deg.
  c = Circle(1.0, 0.0);
  const size_t end = 500 + 1571;
  for (auto* column : {&c.t, &c.delta, &c.x, &c.y, &c.psi}) column->resize(end);
  EXPECT_FALSE(DetectTurningCircle(c.t, c.delta, c.psi, &test, &why));
  EXPECT_EQ(why, "the heading turns less than 90 deg");
}

}  // namespace turning_figures_test
}  // namespace vesselid
