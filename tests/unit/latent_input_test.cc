// The latent input spline (engine/data/latent_input.h) on a smooth signal that is not a
// spline (two sines and a rate-limited step) under white noise: the noise SD is estimated
// within 10 %, the fit is far closer to the signal than the samples are, and a given sigma
// or knot spacing is used as given.
#include "engine/data/latent_input.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace latent_input_test {

double Signal(double t) {
  const double ramp = std::clamp((t - 200.0) / 4.0, 0.0, 1.0);  // 4 s rate-limited step
  return 0.2 * std::sin(2 * M_PI * t / 30.0) + 0.05 * std::sin(2 * M_PI * t / 7.0 + 1.0) +
         0.1 * ramp;
}

Channel Noisy(double sigma, unsigned seed, double rate = 50.0, double duration = 400.0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Channel c;
  for (int k = 0; k * (1.0 / rate) <= duration; ++k) {
    const double t = k / rate;
    c.t.push_back(t);
    c.value.push_back(Signal(t) + noise(rng));
  }
  return c;
}

double RmsError(const LatentInputSpline& s, const Channel& c) {
  double sum = 0.0;
  for (double t : c.t) sum += (s(t) - Signal(t)) * (s(t) - Signal(t));
  return std::sqrt(sum / c.t.size());
}

TEST(LatentInput, RecoversSmoothSignalAndNoiseLevel) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (double sigma : {0.1 * M_PI / 180, 0.5 * M_PI / 180}) {
      const Channel c = Noisy(sigma, seed);
      LatentInputSpline spline;
      std::string error;
      ASSERT_TRUE(spline.Fit(c, {}, &error)) << error;
      EXPECT_NEAR(spline.sigma(), sigma, 0.1 * sigma) << "seed " << seed;
      EXPECT_LT(RmsError(spline, c), 0.3 * sigma) << "seed " << seed;
      EXPECT_GT(spline.knot_spacing(), 0.05);  // smoother than the samples
      EXPECT_LT(spline.knot_spacing(), 7.0 / 2);  // and able to follow the 7 s sine
    }
  }
}

TEST(LatentInput, GivenSigmaAndKnots) {
  const double sigma = 0.2 * M_PI / 180;
  const Channel c = Noisy(sigma, 7);
  LatentInputSpline spline;
  std::string error;
  ASSERT_TRUE(spline.Fit(c, {sigma, 0.0}, &error)) << error;
  EXPECT_EQ(spline.sigma(), sigma);
  EXPECT_LT(RmsError(spline, c), 0.3 * sigma);
  ASSERT_TRUE(spline.Fit(c, {0.0, 0.5}, &error)) << error;
  EXPECT_DOUBLE_EQ(spline.knot_spacing(), 0.5);
  EXPECT_NEAR(spline.sigma(), sigma, 0.1 * sigma);
  // Knots closer than two samples would follow the noise.
  EXPECT_FALSE(spline.Fit(c, {0.0, 0.03}, &error));
  EXPECT_NE(error.find("knots 0.03 s"), std::string::npos) << error;
  Channel few;
  few.t = {0, 1, 2};
  few.value = {0, 1, 2};
  EXPECT_FALSE(spline.Fit(few, {}, &error));
}

TEST(LatentInput, GapsInTheRecordStayDetermined) {
  const double sigma = 0.1 * M_PI / 180;
  Channel c = Noisy(sigma, 4, 10.0, 300.0), gappy;
  for (size_t k = 0; k < c.t.size(); ++k) {
    if (c.t[k] > 100 && c.t[k] < 110) continue;  // a 10 s gap
    gappy.t.push_back(c.t[k]);
    gappy.value.push_back(c.value[k]);
  }
  LatentInputSpline spline;
  std::string error;
  ASSERT_TRUE(spline.Fit(gappy, {0.0, 0.5}, &error)) << error;
  for (double t = 100.0; t < 110.0; t += 0.5) EXPECT_TRUE(std::isfinite(spline(t)));
  EXPECT_NEAR(spline(99.0), Signal(99.0), 5 * sigma);
}

}  // namespace latent_input_test
}  // namespace vesselid
