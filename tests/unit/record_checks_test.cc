// The quantisation rule of record_checks.h: a compass in whole degrees and a rudder in 1-degree
// steps are quantised, with their step; a smooth or noisy channel and a held two-level input
// are not.
#include "engine/run/record_checks.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace {

TEST(RecordChecks, QuantisationStepOfAWholeDegreeCompass) {
  std::vector<double> heading;
  for (int k = 0; k < 600; ++k) heading.push_back(std::round(20.0 * std::sin(0.01 * k)));
  EXPECT_DOUBLE_EQ(QuantisationStep(heading), 1.0);
  // In radians (as the engine holds a degree column), the step is one degree.
  for (double& h : heading) h *= M_PI / 180.0;
  EXPECT_NEAR(QuantisationStep(heading), M_PI / 180.0, 1e-12);
}

TEST(RecordChecks, SmoothNoisyAndTwoLevelChannelsAreNotQuantised) {
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<double> smooth, noisy, two_level;
  for (int k = 0; k < 600; ++k) {
    smooth.push_back(std::sin(0.01 * k));
    noisy.push_back(std::sin(0.01 * k) + noise(random));
    two_level.push_back((k / 50) % 2 == 0 ? 0.35 : -0.35);
  }
  EXPECT_EQ(QuantisationStep(smooth), 0.0);
  EXPECT_EQ(QuantisationStep(noisy), 0.0);
  EXPECT_EQ(QuantisationStep(two_level), 0.0);  // fewer than 3 distinct values
  EXPECT_EQ(QuantisationStep({1.0, 2.0, 3.0}), 0.0);  // too few samples to judge
}

}  // namespace
}  // namespace vesselid
