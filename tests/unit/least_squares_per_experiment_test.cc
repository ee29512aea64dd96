// A least-squares stage with a per-experiment parameter (engine/regression/least_squares.h):
// the rudder bias of Norrbin's n1-form, one intercept column per experiment. Records carry
// the yaw rate and its derivative of three runs with different biases, plus a run whose
// samples are all deselected (its bias is undetermined and said so).
#include <cmath>
#include <random>

#include "engine/regression/least_squares.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace least_squares_per_experiment_test {

constexpr double kT = 80.0, kK = 0.04, kN1 = -0.25, kN3 = 900.0;

// r' = (K (delta + bias) - n1 r - n3 r^3) / T along a rudder sweep (Euler steps of 0.05 s,
// sampled each second), with Gaussian noise on r' of `noise`.
RegressionRecord MakeRun(const std::string& name, double bias, double phase, double noise,
                         unsigned seed) {
  RegressionRecord record;
  record.name = record.record = name;
  const int n = 600;
  record.dt = 1.0;
  record.x = Eigen::MatrixXd::Zero(n, 2);
  record.xdot = Eigen::MatrixXd::Zero(n, 2);
  record.u = Eigen::MatrixXd::Zero(n, 1);
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  double r = 0.0, psi = 0.0;
  auto delta = [&](double t) {
    return 0.3 * std::sin(2 * M_PI * t / 170 + phase) + 0.1 * std::sin(2 * M_PI * t / 47);
  };
  auto rate = [&](double t, double yaw) {
    return (kK * (delta(t) + bias) - kN1 * yaw - kN3 * yaw * yaw * yaw) / kT;
  };
  for (int k = 0; k < n; ++k) {
    const double t = k;
    record.t.push_back(t);
    record.x(k, 0) = psi;
    record.x(k, 1) = r;
    record.u(k, 0) = delta(t);
    record.xdot(k, 0) = r;
    record.xdot(k, 1) = rate(t, r) + gauss(random);
    for (int s = 0; s < 20; ++s) {
      const double h = 0.05;
      r += h * rate(t + s * h, r);
      psi += h * r;
    }
  }
  record.region.assign(n, 0);
  record.use.assign(n, true);
  return record;
}

std::vector<ParameterSpec> Specs() {
  std::vector<ParameterSpec> specs(5);
  const char* names[] = {"T", "K", "n1", "n3", "delta_0"};
  for (int i = 0; i < 5; ++i) specs[i].name = names[i];
  specs[0].start = kT;
  specs[0].role = ParameterRole::kFixed;  // the scale: the data determine K/T, n1/T, n3/T
  specs[1].start = 0.01;
  specs[2].start = 1.0;
  specs[3].start = 0.0;
  specs[4].start = 0.0;
  specs[4].role = ParameterRole::kPerExperiment;
  return specs;
}

TEST(LeastSquaresPerExperiment, OneBiasPerRunAndTheSharedParameters) {
  auto model = nomoto::MakeN1FormHandle(true);
  const double biases[] = {0.03, -0.02, 0.045};
  std::vector<RegressionRecord> records;
  for (int e = 0; e < 3; ++e) {
    records.push_back(MakeRun("run" + std::to_string(e), biases[e], e, 1e-6, 10 + e));
  }
  records.push_back(MakeRun("unused", 0.01, 4, 1e-6, 20));
  records.back().use.assign(records.back().size(), false);
  std::vector<ParameterSpec> specs = Specs();
  specs[4].experiment_starts = {{"run1", -0.01}};  // a carried start
  LeastSquaresResult result;
  LeastSquaresSummary summary;
  ASSERT_TRUE(RunLeastSquares(*model, specs, LeastSquaresOptions(), &records, &result, &summary))
      << summary.message;
  const double truth[] = {kT, kK, kN1, kN3};
  for (int i = 1; i < 4; ++i) {
    EXPECT_LT(std::abs(result.values[i] - truth[i]), 3 * result.std_errors[i] + 1e-12)
        << specs[i].name << " = " << result.values[i] << " +- " << result.std_errors[i];
    EXPECT_LT(std::abs(result.values[i] / truth[i] - 1), 0.01) << specs[i].name;
  }
  ASSERT_EQ(result.per_experiment.size(), 4u);
  for (int e = 0; e < 3; ++e) {
    const ExperimentValue& v = result.per_experiment[e];
    EXPECT_EQ(v.parameter, 4);
    EXPECT_EQ(v.experiment, "run" + std::to_string(e));
    EXPECT_FALSE(v.undetermined);
    EXPECT_LT(std::abs(v.value - biases[e]), 3 * v.std_error + 1e-12) << v.experiment;
    EXPECT_LT(std::abs(v.value - biases[e]), 1e-3) << v.experiment;
  }
  const ExperimentValue& unused = result.per_experiment[3];
  EXPECT_TRUE(unused.undetermined);
  EXPECT_TRUE(std::isnan(unused.std_error));
  bool noted = false;
  for (const std::string& note : summary.notes)
    noted |= note.find("delta_0[unused]") != std::string::npos;
  EXPECT_TRUE(noted);
  // The intercept K delta_0/T has one column per run.
  ASSERT_EQ(summary.equations.size(), 1u);
  EXPECT_EQ(summary.equations[0].coefficients[1], "K*delta_0/T[run0]");
  EXPECT_EQ(summary.equations[0].coefficients.size(), 3u + 4u);
}

// Two runs with the same bias: the per-run values agree with the bias fitted as one shared
// parameter.
TEST(LeastSquaresPerExperiment, SameBiasInEveryRunMatchesTheSharedFit) {
  auto model = nomoto::MakeN1FormHandle(false);
  std::vector<RegressionRecord> records = {MakeRun("a", 0.02, 0, 1e-6, 1),
                                           MakeRun("b", 0.02, 1, 1e-6, 2)};
  std::vector<ParameterSpec> specs = Specs();
  specs.erase(specs.begin() + 3);  // first order: T K n1 delta_0
  LeastSquaresResult per_run, shared;
  LeastSquaresSummary summary;
  ASSERT_TRUE(RunLeastSquares(*model, specs, LeastSquaresOptions(), &records, &per_run, &summary))
      << summary.message;
  specs[3].role = ParameterRole::kFree;
  ASSERT_TRUE(RunLeastSquares(*model, specs, LeastSquaresOptions(), &records, &shared, &summary))
      << summary.message;
  // Same bias in both runs: the per-run values agree with the shared one.
  for (const ExperimentValue& v : per_run.per_experiment) {
    EXPECT_NEAR(v.value, shared.values[3], 4 * v.std_error) << v.experiment;
  }
  EXPECT_TRUE(shared.per_experiment.empty());
}

}  // namespace least_squares_per_experiment_test
}  // namespace vesselid
