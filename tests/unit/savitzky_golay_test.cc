// Savitzky-Golay smoothing and differentiation: exact on polynomials up to the order (ends
// included), noise reduction as the theory gives, and clear errors for unusable options.
#include "engine/data/savitzky_golay.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace savitzky_golay_test {

std::vector<double> Sample(double dt, int n, double (*f)(double)) {
  std::vector<double> y(n);
  for (int k = 0; k < n; ++k) y[k] = f(k * dt);
  return y;
}

double Cubic(double t) { return 1.0 - 2.0 * t + 0.5 * t * t - 0.1 * t * t * t; }
double CubicRate(double t) { return -2.0 + t - 0.3 * t * t; }
double CubicAcceleration(double t) { return 1.0 - 0.6 * t; }

TEST(SavitzkyGolay, ExactOnPolynomialsUpToItsOrderIncludingTheEnds) {
  const double dt = 0.2;
  const std::vector<double> y = Sample(dt, 40, Cubic);
  std::string error;
  std::vector<double> value, rate, acceleration;
  ASSERT_TRUE(SavitzkyGolay(y, dt, {4, 3, 0}, &value, &error)) << error;
  ASSERT_TRUE(SavitzkyGolay(y, dt, {4, 3, 1}, &rate, &error)) << error;
  ASSERT_TRUE(SavitzkyGolay(y, dt, {4, 3, 2}, &acceleration, &error)) << error;
  ASSERT_EQ(value.size(), y.size());
  for (int k = 0; k < 40; ++k) {
    EXPECT_NEAR(value[k], Cubic(k * dt), 1e-10) << k;
    EXPECT_NEAR(rate[k], CubicRate(k * dt), 1e-9) << k;
    EXPECT_NEAR(acceleration[k], CubicAcceleration(k * dt), 1e-8) << k;
  }
}

TEST(SavitzkyGolay, NoiseOfTheCentredRateFollowsTheLeastSquaresFormula) {
  // Quadratic fit, centre point: var(slope) = sigma^2 / (dt^2 sum s^2), sum s^2 = m(m+1)(2m+1)/3.
  const int m = 10, n = 20000;
  const double dt = 0.1, sigma = 0.05;
  std::mt19937_64 random(7);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> y(n);
  for (double& v : y) v = noise(random);
  std::vector<double> rate;
  std::string error;
  ASSERT_TRUE(SavitzkyGolay(y, dt, {m, 2, 1}, &rate, &error)) << error;
  double sum = 0.0;
  for (int k = m; k < n - m; ++k) sum += rate[k] * rate[k];
  const double measured = std::sqrt(sum / (n - 2 * m));
  const double expected = sigma / (dt * std::sqrt(m * (m + 1) * (2 * m + 1) / 3.0));
  EXPECT_NEAR(measured / expected, 1.0, 0.05);
}

TEST(SavitzkyGolay, RejectsOptionsThatDoNotFitTheData) {
  std::vector<double> out;
  std::string error;
  EXPECT_FALSE(SavitzkyGolay(std::vector<double>(5, 0.0), 0.1, {3, 2, 0}, &out, &error));
  EXPECT_NE(error.find("window of 7 samples is longer than the 5 samples"), std::string::npos);
  EXPECT_FALSE(SavitzkyGolay(std::vector<double>(50, 0.0), 0.1, {2, 5, 0}, &out, &error));
  EXPECT_FALSE(SavitzkyGolay(std::vector<double>(50, 0.0), 0.1, {3, 2, 3}, &out, &error));
  EXPECT_FALSE(SavitzkyGolay(std::vector<double>(50, 0.0), 0.0, {3, 2, 1}, &out, &error));
}

}  // namespace savitzky_golay_test
}  // namespace vesselid
