// The test behind the noisy-input finding (engine/diagnose/input_noise_findings.h): white noise on
// a measured rudder is found with its SD, clean, held (zigzag) and quantised (PWM) inputs are
// passed over, and slow residuals are told from white ones.
#include "engine/diagnose/input_noise_findings.h"
#include "engine/data/white_noise.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace input_noise_findings_test {

constexpr double kDeg = M_PI / 180;

// A closed-loop-like rudder at 50 Hz: a few sines through a first-order lag.
std::vector<double> SmoothRudder(int n) {
  std::vector<double> u(n);
  double lag = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = 0.02 * k;
    const double command = 10 * kDeg * (std::sin(2 * M_PI * t / 40) + 0.3 * std::sin(2 * M_PI * t / 7));
    lag += 0.02 / 2.0 * (command - lag);
    u[k] = lag;
  }
  return u;
}

// A zigzag rudder: held at +-20 deg, moved at 3 deg/s between.
std::vector<double> Zigzag(int n) {
  std::vector<double> u(n);
  double rudder = 0.0, target = 20 * kDeg;
  for (int k = 0; k < n; ++k) {
    if (k % 1500 == 0) target = -target;
    const double step = 3 * kDeg * 0.02;
    rudder += std::clamp(target - rudder, -step, step);
    u[k] = rudder;
  }
  return u;
}

void AddNoise(double sigma, unsigned seed, std::vector<double>* u) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (double& v : *u) v += noise(rng);
}

TEST(InputNoiseWarning, FindsWhiteNoiseOnARudder) {
  for (double sigma : {0.1 * kDeg, 0.5 * kDeg}) {
    std::vector<double> u = SmoothRudder(20000);
    AddNoise(sigma, 3, &u);
    EXPECT_NEAR(WhiteInputNoise(u), sigma, 0.1 * sigma);
    std::vector<double> z = Zigzag(20000);
    AddNoise(sigma, 4, &z);
    EXPECT_NEAR(WhiteInputNoise(z), sigma, 0.1 * sigma);
  }
}

// A logger that writes exact zeros while the rudder rests (a third of the record) and the
// noisy angle otherwise: the noise is found on the stretches between the zeros.
TEST(InputNoiseWarning, FindsTheNoiseBetweenExactZeros) {
  const double sigma = 0.15 * kDeg;
  std::vector<double> z = Zigzag(6000);
  AddNoise(sigma, 9, &z);
  for (size_t k = 2000; k < 4000; ++k) z[k] = 0.0;
  EXPECT_NEAR(WhiteInputNoise(z), sigma, 0.15 * sigma);
}

TEST(InputNoiseWarning, QuietOnCleanHeldAndQuantisedInputs) {
  EXPECT_EQ(WhiteInputNoise(SmoothRudder(20000)), 0.0);
  EXPECT_EQ(WhiteInputNoise(Zigzag(20000)), 0.0);
  // PWM commands: steps between a few levels, held for seconds.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> level(-4, 4);
  std::vector<double> pwm;
  for (int segment = 0; segment < 100; ++segment) {
    const double value = 0.25 * level(rng);
    for (int k = 0; k < 100; ++k) pwm.push_back(value);
  }
  EXPECT_EQ(WhiteInputNoise(pwm), 0.0);
  // A rudder logged with 0.1 deg resolution (quantised, not noisy).
  std::vector<double> coarse = SmoothRudder(20000);
  for (double& v : coarse) v = std::round(v / (0.1 * kDeg)) * 0.1 * kDeg;
  EXPECT_EQ(WhiteInputNoise(coarse), 0.0);
  // Noise far below the signal's size does not matter.
  std::vector<double> faint = SmoothRudder(20000);
  AddNoise(1e-4 * 10 * kDeg, 6, &faint);
  EXPECT_EQ(WhiteInputNoise(faint), 0.0);
}

TEST(InputNoiseWarning, ColouredResiduals) {
  std::vector<double> white(6000, 0.0), walk(6000, 0.0);
  AddNoise(0.1 * kDeg, 7, &white);
  std::mt19937 rng(8);
  std::normal_distribution<double> step(0.0, 0.01 * kDeg);
  double w = 0.0;
  for (size_t k = 0; k < walk.size(); ++k) {
    w += step(rng);
    walk[k] = white[k] + w;
  }
  EXPECT_FALSE(ResidualsColoured(white));
  EXPECT_TRUE(ResidualsColoured(walk));
  EXPECT_FALSE(ResidualsColoured(std::vector<double>(100, 0.0)));  // too short to tell
}

}  // namespace input_noise_findings_test
}  // namespace vesselid
