// Seed 004's measurement extraction on synthetic step records: a first-order plant per signal
// (speed U driven by throttle, yaw rate r by rudder) with known time constant and gain, stepped
// up and down at 5 Hz with Gaussian noise and optionally a sinusoidal "current" on U. Checks the
// constant-input intervals, the steady windows and their means (damping data), and the
// first-order step fit (inertia data), alone and chained as the seed does.
#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "engine/base/nan.h"
#include "engine/step_regression/first_order_step.h"
#include "engine/step_regression/steady_state.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace step_samples_test {

constexpr double kDt = 0.2;  // 5 Hz
constexpr double kPi = 3.14159265358979323846;

struct Plant {
  double time_constant;
  double gain;  // steady signal per unit input
};
const Plant kSpeed{8.0, 10.0};  // U: T = 8 s, 10 m/s per unit throttle
const Plant kYaw{4.0, 0.2};     // r: T = 4 s, 0.2 rad/s per unit rudder

struct Level {
  double duration;  // s
  double throttle, rudder;
};

struct RecordOptions {
  double noise_speed = 0.01, noise_yaw = 0.0005;  // SD of the measurement noise
  double current_amplitude = 0.0;                 // on U, A sin(2 pi t / period)
  double current_period = 60.0;
  unsigned seed = 7;
};

struct Record {
  std::vector<double> t;
  Eigen::MatrixXd signals, truth, inputs;  // truth: noiseless first-order responses
  std::vector<int> step_rows;              // first row of each level
};

// Exact zero-order-hold solution: the input of row k acts on [t_k, t_k+1), the plant starts at
// rest on the first level.
Record Simulate(const std::vector<Level>& levels, const RecordOptions& options = {}) {
  Record record;
  int n = 0;
  for (const Level& level : levels) {
    record.step_rows.push_back(n);
    n += static_cast<int>(std::lround(level.duration / kDt));
  }
  record.t.resize(n);
  record.signals.resize(n, 2);
  record.truth.resize(n, 2);
  record.inputs.resize(n, 2);
  std::mt19937 rng(options.seed);
  std::normal_distribution<double> normal;
  const Plant plants[2] = {kSpeed, kYaw};
  double y[2] = {kSpeed.gain * levels[0].throttle, kYaw.gain * levels[0].rudder};
  int k = 0;
  for (const Level& level : levels) {
    const int rows = static_cast<int>(std::lround(level.duration / kDt));
    const double u[2] = {level.throttle, level.rudder};
    for (int r = 0; r < rows; ++r, ++k) {
      record.t[k] = k * kDt;
      for (int i = 0; i < 2; ++i) {
        record.inputs(k, i) = u[i];
        record.truth(k, i) = y[i];
        const double steady = plants[i].gain * u[i];
        y[i] = steady + (y[i] - steady) * std::exp(-kDt / plants[i].time_constant);
      }
      record.signals(k, 0) =
          record.truth(k, 0) + options.noise_speed * normal(rng) +
          options.current_amplitude * std::sin(2.0 * kPi * record.t[k] / options.current_period);
      record.signals(k, 1) = record.truth(k, 1) + options.noise_yaw * normal(rng);
    }
  }
  return record;
}

// Throttle up and down at a fixed rudder, then rudder up and down at a fixed throttle.
std::vector<Level> StepLevels(double hold) {
  return {{hold, 0.2, 0.1}, {hold, 0.3, 0.1}, {hold, 0.4, 0.1}, {hold, 0.3, 0.1},
          {hold, 0.3, 0.3}, {hold, 0.3, 0.5}, {hold, 0.3, 0.3}};
}

double TrueSteady(const std::vector<double>& input, int signal) {
  return signal == 0 ? kSpeed.gain * input[0] : kYaw.gain * input[1];
}

// The window starts with a residual transient of about the band (plus smoothed noise) that
// decays with T, so it moves the window mean off the steady value by at most ~1.5 band T / W.
double TransientBias(const InputInterval& interval, int signal) {
  const Plant plant = signal == 0 ? kSpeed : kYaw;
  return 1.5 * interval.band[signal] * plant.time_constant / (interval.t_end - interval.t_steady);
}

// How far a steady mean may sit from the true steady value: 4 noise SEs over `count` samples
// plus the residual-transient bias.
double MeanTolerance(const InputInterval& interval, int signal, double noise, int count) {
  return 4.0 * noise / std::sqrt(count) + TransientBias(interval, signal);
}

bool Find(const Record& record, const SteadyStateOptions& options,
          std::vector<InputInterval>* intervals, std::string* error) {
  return FindSteadyStates(record.t, record.signals, record.inputs, options, intervals, error);
}

// ---------------------------------------------------------------- FindSteadyStates

TEST(SteadyStates, IntervalsMatchTheStepTimesExactly) {
  std::vector<Level> levels = StepLevels(60.0);
  levels.push_back({40.0, 0.5, 0.0});  // both inputs change together
  const Record record = Simulate(levels);
  std::vector<InputInterval> intervals;
  std::string error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), levels.size());
  for (size_t j = 0; j < levels.size(); ++j) {
    const int end = j + 1 < levels.size() ? record.step_rows[j + 1] : record.t.size();
    EXPECT_EQ(intervals[j].begin, record.step_rows[j]) << j;
    EXPECT_EQ(intervals[j].end, end) << j;
    EXPECT_EQ(intervals[j].t_begin, record.t[record.step_rows[j]]) << j;
    EXPECT_EQ(intervals[j].t_end, record.t[end - 1]) << j;
    ASSERT_EQ(intervals[j].input.size(), 2u);
    EXPECT_EQ(intervals[j].input[0], levels[j].throttle) << j;
    EXPECT_EQ(intervals[j].input[1], levels[j].rudder) << j;
  }
}

TEST(SteadyStates, SmallInputJitterWithinTheToleranceDoesNotSplit) {
  Record record = Simulate({{60.0, 0.2, 0.1}, {60.0, 0.3, 0.1}});
  for (int k = 0; k < record.inputs.rows(); k += 3) record.inputs(k, 0) += 1e-4;
  std::vector<InputInterval> intervals;
  std::string error;
  SteadyStateOptions options;
  ASSERT_TRUE(Find(record, options, &intervals, &error)) << error;
  EXPECT_GT(intervals.size(), 2u);  // 1e-4 > default tolerance: every jitter splits
  options.input_tolerance = 1e-3;
  ASSERT_TRUE(Find(record, options, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), 2u);
  EXPECT_EQ(intervals[1].begin, record.step_rows[1]);
}

TEST(SteadyStates, WindowsStartAfterSettlingAndEndAtTheIntervalEnd) {
  const Record record = Simulate(StepLevels(120.0));
  std::vector<InputInterval> intervals;
  std::string error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), 7u);
  // The first level starts at rest: steady from (almost) its first row.
  ASSERT_TRUE(intervals[0].steady);
  EXPECT_LT(intervals[0].t_steady - intervals[0].t_begin, 1.0);
  for (size_t j = 1; j < intervals.size(); ++j) {
    const InputInterval& interval = intervals[j];
    ASSERT_TRUE(interval.steady) << j;
    EXPECT_LT(interval.steady_begin, interval.end) << j;
    EXPECT_EQ(interval.t_steady, record.t[interval.steady_begin]) << j;
    // The stepped signal: band about 2 noise SDs, and the smoothed transient
    // |dy| exp(-(t - t_step) / T) leaves it after T ln(|dy| / band), here 3.7 to 3.9 T.
    const int i = j <= 3 ? 0 : 1;
    const Plant plant = i == 0 ? kSpeed : kYaw;
    const double noise = i == 0 ? 0.01 : 0.0005;
    EXPECT_NEAR(interval.band[i], 2.0 * noise, 0.3 * noise) << j;
    const double change = TrueSteady(interval.input, i) - TrueSteady(intervals[j - 1].input, i);
    const double expected = plant.time_constant * std::log(std::abs(change) / interval.band[i]);
    const double settle = interval.t_steady - interval.t_begin;
    // The last noisy exceedance scatters the crossing: -0.3 T to +0.4 T in 99 % of 300 records.
    EXPECT_GT(settle - expected, -0.4 * plant.time_constant) << j;
    EXPECT_LT(settle - expected, 0.6 * plant.time_constant) << j;
    EXPECT_GT(settle, 3.0 * plant.time_constant) << j;
    EXPECT_LT(settle, 5.0 * plant.time_constant) << j;
  }
}

TEST(SteadyStates, MeansEqualTheTrueSteadyValuesWithinTheNoise) {
  const Record record = Simulate(StepLevels(120.0));
  std::vector<InputInterval> intervals;
  std::string error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  for (size_t j = 0; j < intervals.size(); ++j) {
    const InputInterval& interval = intervals[j];
    ASSERT_TRUE(interval.steady) << j;
    const int count = interval.end - interval.steady_begin;
    for (int i = 0; i < 2; ++i) {
      const double noise = i == 0 ? 0.01 : 0.0005;
      // The mean is the window's average: within 4 noise SEs of the noiseless average...
      const Eigen::VectorXd truth = record.truth.col(i).segment(interval.steady_begin, count);
      EXPECT_NEAR(interval.mean[i], truth.mean(), 4.0 * noise / std::sqrt(count)) << j << " " << i;
      // ... which the residual transient moves off the steady value by at most ~band T / W.
      const double steady = TrueSteady(interval.input, i);
      EXPECT_LT(std::abs(truth.mean() - steady), TransientBias(interval, i)) << j << " " << i;
      EXPECT_NEAR(interval.mean[i], steady, MeanTolerance(interval, i, noise, count))
          << j << " " << i;
      // The SD holds the noise and the residual transient (its own SE is about 3.4 % here).
      const double spread = (truth.array() - truth.mean()).square().mean();
      // Measured at most 0.093 of the noise over these intervals (2.7 of the SD's own SE):
      // 0.15 is 4.4 SE.
      EXPECT_NEAR(interval.sd[i], std::sqrt(noise * noise + spread), 0.15 * noise) << j << " " << i;
    }
  }
}

TEST(SteadyStates, CurrentOscillationIsAveragedOverFullTurns) {
  // Circling in a current: U oscillates with the turn period (60 s, amplitude 0.05 > 4 noise
  // SDs) at steady state; each level is held for three turns.
  RecordOptions record_options;
  record_options.current_amplitude = 0.05;
  record_options.current_period = 60.0;
  const Record record = Simulate(StepLevels(180.0), record_options);
  std::vector<InputInterval> intervals;
  std::string error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), 7u);
  for (size_t j = 0; j < intervals.size(); ++j) {
    const InputInterval& interval = intervals[j];
    ASSERT_TRUE(interval.steady) << j;
    const double window = interval.t_end - interval.t_steady;
    EXPECT_GE(window, 2.0 * record_options.current_period) << j;
    // Mean over a window of length W: the sinusoid leaves at most A P / (pi W), the residual
    // transient about band T / W.
    const double bound =
        record_options.current_amplitude * record_options.current_period / (kPi * window) +
        interval.band[0] * kSpeed.time_constant / window +
        4.0 * 0.01 / std::sqrt(interval.end - interval.steady_begin);
    EXPECT_NEAR(interval.mean[0], TrueSteady(interval.input, 0), bound) << j;
  }
  // A fixed band below the oscillation amplitude never holds for a full turn.
  SteadyStateOptions fixed;
  fixed.band_factor = 0.0;
  fixed.tolerance = {0.04, 0.002};
  ASSERT_TRUE(Find(record, fixed, &intervals, &error)) << error;
  for (size_t j = 0; j < intervals.size(); ++j) {
    EXPECT_LT(intervals[j].t_end - intervals[j].t_steady, record_options.current_period) << j;
  }
}

TEST(SteadyStates, TooShortIntervalsAreNotSteady) {
  const Record record =
      Simulate({{60.0, 0.2, 0.1}, {6.0, 0.3, 0.1}, {60.0, 0.3, 0.3}, {30.0, 0.4, 0.3}});
  std::vector<InputInterval> intervals;
  std::string error;
  SteadyStateOptions options;
  ASSERT_TRUE(Find(record, options, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), 4u);
  EXPECT_TRUE(intervals[0].steady);
  EXPECT_FALSE(intervals[1].steady);  // 6 s < min_duration = 10 s
  EXPECT_TRUE(std::isnan(intervals[1].mean[0]) && std::isnan(intervals[1].sd[1]));
  EXPECT_TRUE(intervals[2].steady);
  // The last level's U transient takes well over 5 s of its 30 s, so no window of 25 s exists.
  options.min_duration = 25.0;
  ASSERT_TRUE(Find(record, options, &intervals, &error)) << error;
  EXPECT_TRUE(intervals[2].steady);
  EXPECT_FALSE(intervals[3].steady);
  EXPECT_GT(intervals[3].t_steady - intervals[3].t_begin, 5.0);
  EXPECT_TRUE(std::isnan(intervals[3].mean[0]));
  // A whole record shorter than min_duration.
  const Record brief = Simulate({{8.0, 0.2, 0.1}});
  options.min_duration = 10.0;
  ASSERT_TRUE(Find(brief, options, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), 1u);
  EXPECT_FALSE(intervals[0].steady);
}

TEST(SteadyStates, MissingSamplesAreSkipped) {
  const Record clean = Simulate(StepLevels(120.0));
  Record record = clean;
  std::mt19937 rng(3);
  std::bernoulli_distribution missing(0.1);
  for (int k = 0; k < record.signals.rows(); ++k) {
    for (int i = 0; i < 2; ++i) {
      if (missing(rng)) record.signals(k, i) = kNaN;
    }
  }
  // A 20 s gap in U in the steady part of level 2 (longer than the smoothing).
  const int gap = record.step_rows[2] + 400;
  for (int k = gap; k < gap + 100; ++k) record.signals(k, 0) = kNaN;

  std::vector<InputInterval> reference, intervals;
  std::string error;
  ASSERT_TRUE(Find(clean, {}, &reference, &error)) << error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  ASSERT_EQ(intervals.size(), reference.size());
  for (size_t j = 0; j < intervals.size(); ++j) {
    ASSERT_TRUE(intervals[j].steady) << j;
    // Both settle times scatter by about +-0.3 T (see above).
    EXPECT_NEAR(intervals[j].t_steady, reference[j].t_steady, 0.6 * kSpeed.time_constant) << j;
    for (int i = 0; i < 2; ++i) {
      const double noise = i == 0 ? 0.01 : 0.0005;
      ASSERT_TRUE(std::isfinite(intervals[j].mean[i])) << j;
      int count = 0;
      for (int k = intervals[j].steady_begin; k < intervals[j].end; ++k) {
        count += std::isnan(record.signals(k, i)) ? 0 : 1;
      }
      EXPECT_NEAR(intervals[j].mean[i], TrueSteady(intervals[j].input, i),
                  MeanTolerance(intervals[j], i, noise, count))
          << j << " " << i;
    }
  }

  // A signal missing altogether: no band, no mean; the other signal still decides.
  record = clean;
  record.signals.col(1).setConstant(kNaN);
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  for (size_t j = 0; j < intervals.size(); ++j) {
    EXPECT_TRUE(intervals[j].steady) << j;
    EXPECT_TRUE(std::isnan(intervals[j].band[1]) && std::isnan(intervals[j].mean[1])) << j;
    EXPECT_NEAR(intervals[j].mean[0], TrueSteady(intervals[j].input, 0),
                MeanTolerance(intervals[j], 0, 0.01, intervals[j].end - intervals[j].steady_begin))
        << j;
  }
  // Every signal missing: nothing can be steady.
  record.signals.setConstant(kNaN);
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  for (const InputInterval& interval : intervals) {
    EXPECT_FALSE(interval.steady);
    EXPECT_EQ(interval.steady_begin, interval.end);
  }
}

TEST(SteadyStates, AveragesOfAFewSamplesInAGapAreNotTested) {
  // A 20 s gap in U in the steady part of level 2 with one lone sample 3 noise SDs high in it:
  // rows whose 5 s average holds only that sample must not end the steady window.
  const Record clean = Simulate(StepLevels(120.0));
  Record record = clean;
  const int gap = record.step_rows[2] + 400;
  for (int k = gap; k < gap + 100; ++k) record.signals(k, 0) = kNaN;
  record.signals(gap + 50, 0) = record.truth(gap + 50, 0) + 3.0 * 0.01;
  std::vector<InputInterval> reference, intervals;
  std::string error;
  ASSERT_TRUE(Find(clean, {}, &reference, &error)) << error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  ASSERT_TRUE(intervals[2].steady);
  // The gap changes the last half's SD a little, hence the band and the settle point.
  EXPECT_NEAR(intervals[2].t_steady, reference[2].t_steady, 2.0);
  EXPECT_LT(intervals[2].steady_begin, gap);
}

TEST(SteadyStates, LongRecordsTakeLinearTime) {
  // 1e5 rows, 100 levels of 200 s: a quadratic moving average would take minutes.
  std::vector<Level> levels;
  for (int j = 0; j < 100; ++j) levels.push_back({200.0, 0.2 + 0.1 * (j % 5), 0.1 * (j % 3)});
  const Record record = Simulate(levels);
  ASSERT_EQ(record.t.size(), 100000u);
  std::vector<InputInterval> intervals;
  std::string error;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(intervals.size(), 100u);
  for (const InputInterval& interval : intervals) EXPECT_TRUE(interval.steady);
  EXPECT_LT(seconds, 2.0);
}

TEST(SteadyStates, BadInputsGiveFalseAndAMessage) {
  const Record record = Simulate({{30.0, 0.2, 0.1}, {30.0, 0.3, 0.1}});
  std::vector<InputInterval> intervals;
  std::string error;
  auto fails = [&](const std::vector<double>& t, const Eigen::MatrixXd& signals,
                   const Eigen::MatrixXd& inputs, const SteadyStateOptions& options,
                   const std::string& word) {
    error.clear();
    const bool ok = FindSteadyStates(t, signals, inputs, options, &intervals, &error);
    return !ok && error.find(word) != std::string::npos;
  };
  const SteadyStateOptions options;
  EXPECT_TRUE(fails(record.t, record.signals.topRows(10), record.inputs, options, "rows")) << error;
  EXPECT_TRUE(fails({}, Eigen::MatrixXd(0, 2), Eigen::MatrixXd(0, 2), options, "no rows")) << error;
  std::vector<double> t = record.t;
  t[50] = t[49];
  EXPECT_TRUE(fails(t, record.signals, record.inputs, options, "increasing")) << error;
  t = record.t;
  t[50] = kNaN;
  EXPECT_TRUE(fails(t, record.signals, record.inputs, options, "not finite")) << error;
  Eigen::MatrixXd inputs = record.inputs;
  inputs(20, 1) = kNaN;
  EXPECT_TRUE(fails(record.t, record.signals, inputs, options, "input 1 at row 20")) << error;
  Eigen::MatrixXd signals = record.signals;
  signals(20, 0) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(fails(record.t, signals, record.inputs, options, "infinite")) << error;
  SteadyStateOptions bad = options;
  bad.tolerance = {0.1};
  EXPECT_TRUE(fails(record.t, record.signals, record.inputs, bad, "tolerance")) << error;
  bad = options;
  bad.smoothing = -1.0;
  EXPECT_FALSE(bad.IsValid(&error));
  EXPECT_TRUE(fails(record.t, record.signals, record.inputs, bad, "smoothing")) << error;
  bad = options;
  bad.tolerance = {0.1, kNaN};
  EXPECT_TRUE(fails(record.t, record.signals, record.inputs, bad, "tolerance[1]")) << error;
  EXPECT_TRUE(options.IsValid(&error));
}

// ---------------------------------------------------------------- FitFirstOrderStep

struct StepSamples {
  std::vector<double> t, y;
};

// y_before until t_step, then the first-order response; times every kDt from 0 to `length`.
StepSamples StepResponse(double t_step, double y_before, double y_after, double time_constant,
                         double length, double noise, unsigned seed) {
  StepSamples samples;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  for (int k = 0; k * kDt <= length + 1e-9; ++k) {
    const double t = k * kDt;
    double y = y_before;
    if (t >= t_step) y += (y_after - y_before) * (1.0 - std::exp(-(t - t_step) / time_constant));
    samples.t.push_back(t);
    samples.y.push_back(y + noise * normal(rng));
  }
  return samples;
}

TEST(FirstOrderStep, RecoversTheTimeConstantExactlyFromNoiselessData) {
  StepSamples samples = StepResponse(10.0, 2.0, 3.0, 7.3, 70.0, 0.0, 1);
  for (size_t k = 0; k < samples.t.size() && samples.t[k] < 9.9; ++k) samples.y[k] = 100.0;
  FirstOrderStepFit fit;
  std::string error;
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 10.0, 2.0, 3.0, 0.1, {}, &fit, &error))
      << error;
  EXPECT_NEAR(fit.time_constant, 7.3, 7.3e-6);
  EXPECT_DOUBLE_EQ(fit.gain, 0.1);  // du / dy
  EXPECT_NEAR(fit.inertia, 0.73, 0.73e-6);
  EXPECT_LT(fit.rms, 1e-9);
  EXPECT_EQ(fit.samples, 301);  // t = 10 ... 70 (samples before the step are ignored)
  EXPECT_FALSE(fit.at_bound);
}

TEST(FirstOrderStep, RecoversTheTimeConstantWithinAFewPercentFromNoisyData) {
  // Noise 2 % of the step: the Cramer-Rao SD of T is about 0.6 % here.
  double mean_error = 0.0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const StepSamples samples = StepResponse(10.0, 5.0, 4.0, 8.0, 70.0, 0.02, seed);
    FirstOrderStepFit fit;
    std::string error;
    ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 10.0, 5.0, 4.0, -0.1, {}, &fit, &error))
        << error;
    EXPECT_NEAR(fit.time_constant, 8.0, 0.03 * 8.0) << seed;
    EXPECT_NEAR(fit.inertia, 0.8, 0.03 * 0.8) << seed;
    EXPECT_NEAR(fit.rms, 0.02, 0.003) << seed;
    EXPECT_FALSE(fit.at_bound);
    mean_error += (fit.time_constant - 8.0) / 20.0;
  }
  EXPECT_LT(std::abs(mean_error), 0.01 * 8.0);
}

TEST(FirstOrderStep, NegativeGainIsReportedAsComputed) {
  // The response goes against the input: k < 0, m = k T < 0, T itself is recovered.
  const StepSamples samples = StepResponse(0.0, 1.0, 0.5, 3.0, 30.0, 0.0, 1);
  FirstOrderStepFit fit;
  std::string error;
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 0.0, 1.0, 0.5, 0.2, {}, &fit, &error))
      << error;
  EXPECT_NEAR(fit.time_constant, 3.0, 3e-6);
  EXPECT_DOUBLE_EQ(fit.gain, -0.4);
  EXPECT_NEAR(fit.inertia, -1.2, 1.2e-6);
}

TEST(FirstOrderStep, TimeConstantOutsideTheRangeIsAtTheBound) {
  FirstOrderStepFit fit;
  std::string error;
  StepSamples samples = StepResponse(0.0, 0.0, 1.0, 1000.0, 60.0, 0.0, 1);
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, {}, &fit, &error));
  EXPECT_TRUE(fit.at_bound);
  EXPECT_EQ(fit.time_constant, 300.0);
  samples = StepResponse(0.0, 0.0, 1.0, 0.01, 60.0, 0.0, 1);
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, {}, &fit, &error));
  EXPECT_TRUE(fit.at_bound);
  EXPECT_EQ(fit.time_constant, 0.05);
  // Inside a narrowed range it is not.
  samples = StepResponse(0.0, 0.0, 1.0, 2.0, 60.0, 0.0, 1);
  FirstOrderStepOptions options;
  options.min_time_constant = 1.0;
  options.max_time_constant = 4.0;
  options.grid = 5;
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, options, &fit, &error));
  EXPECT_FALSE(fit.at_bound);
  EXPECT_NEAR(fit.time_constant, 2.0, 2e-6);
}

TEST(FirstOrderStep, MissingSamplesAreSkipped) {
  StepSamples samples = StepResponse(5.0, 0.0, 2.0, 4.0, 40.0, 0.0, 1);
  int missing = 0;
  for (size_t k = 0; k < samples.y.size(); k += 4, ++missing) samples.y[k] = kNaN;
  FirstOrderStepFit fit;
  std::string error;
  ASSERT_TRUE(FitFirstOrderStep(samples.t, samples.y, 5.0, 0.0, 2.0, 1.0, {}, &fit, &error))
      << error;
  EXPECT_NEAR(fit.time_constant, 4.0, 4e-6);
  EXPECT_EQ(fit.samples, 176 - 44);  // 176 samples from t = 5 to 40, every 4th row missing
}

TEST(FirstOrderStep, BadInputsGiveFalseAndAMessage) {
  const StepSamples samples = StepResponse(0.0, 0.0, 1.0, 2.0, 20.0, 0.0, 1);
  FirstOrderStepFit fit;
  std::string error;
  auto fails = [&](const std::vector<double>& t, const std::vector<double>& y, double t_step,
                   double before, double after, double du, const FirstOrderStepOptions& options,
                   const std::string& word) {
    error.clear();
    return !FitFirstOrderStep(t, y, t_step, before, after, du, options, &fit, &error) &&
           error.find(word) != std::string::npos;
  };
  const FirstOrderStepOptions options;
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 1.0, 1.0, 1.0, options, "response change"));
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 0.0, kNaN, 1.0, options, "finite"));
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 0.0, 1.0, 0.0, options, "input change"));
  EXPECT_TRUE(fails(samples.t, samples.y, 19.7, 0.0, 1.0, 1.0, options, "2 usable samples"));
  std::vector<double> y = samples.y;
  for (double& value : y) value = kNaN;
  EXPECT_TRUE(fails(samples.t, y, 0.0, 0.0, 1.0, 1.0, options, "0 usable samples"));
  EXPECT_TRUE(fails(samples.t, {1.0, 2.0}, 0.0, 0.0, 1.0, 1.0, options, "samples"));
  FirstOrderStepOptions bad;
  bad.max_time_constant = bad.min_time_constant;
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, bad, "max_time_constant"));
  bad = FirstOrderStepOptions();
  bad.grid = 1;
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, bad, "grid"));
  bad = FirstOrderStepOptions();
  bad.min_time_constant = 0.0;
  EXPECT_TRUE(fails(samples.t, samples.y, 0.0, 0.0, 1.0, 1.0, bad, "min_time_constant"));
}

// ---------------------------------------------------------------- The seed's chain

TEST(StepSamples, SteadyMeansAndStepFitsGiveTheDampingAndInertiaOfThePlant) {
  // Damping data: sigma = tau at steady state, x = window means. Inertia data: for each step,
  // k = du / (x+ - x-) from the neighbouring steady means, T from the transient, m = k T.
  const Record record = Simulate(StepLevels(120.0));
  std::vector<InputInterval> intervals;
  std::string error;
  ASSERT_TRUE(Find(record, {}, &intervals, &error)) << error;
  int fits = 0;
  for (size_t j = 1; j < intervals.size(); ++j) {
    const InputInterval& before = intervals[j - 1];
    const InputInterval& after = intervals[j];
    ASSERT_TRUE(before.steady && after.steady) << j;
    const int i = after.input[0] != before.input[0] ? 0 : 1;  // the stepped input and signal
    const Plant plant = i == 0 ? kSpeed : kYaw;
    const std::vector<double> t(record.t.begin() + after.begin, record.t.begin() + after.end);
    std::vector<double> y(t.size());
    for (size_t k = 0; k < t.size(); ++k) y[k] = record.signals(after.begin + k, i);
    FirstOrderStepFit fit;
    ASSERT_TRUE(FitFirstOrderStep(t, y, after.t_begin, before.mean[i], after.mean[i],
                                  after.input[i] - before.input[i], {}, &fit, &error))
        << error;
    // Linearised damping of y = gain u: k = 1 / gain; inertia m = T / gain.
    EXPECT_NEAR(fit.gain, 1.0 / plant.gain, 0.01 / plant.gain) << j;
    EXPECT_NEAR(fit.time_constant, plant.time_constant, 0.03 * plant.time_constant) << j;
    EXPECT_NEAR(fit.inertia, plant.time_constant / plant.gain,
                0.04 * plant.time_constant / plant.gain)
        << j;
    ++fits;
  }
  EXPECT_EQ(fits, 6);
}

}  // namespace step_samples_test
}  // namespace vesselid
