// Angles compared as angles: a measured heading is unwrapped when an experiment is built, and
// a simulated heading whole turns off is scored as turns off, not as nearly perfect; wrapping
// the residual is an explicit choice per output. Records split by a segment column are cut
// into continuation pieces too. Data: the first-order Nomoto step response in closed form
// (not the engine's integrator), heading stored wrapped to (-pi, pi] as a compass logs it.
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "engine/base/angle.h"
#include "engine/model/experiment.h"
#include "engine/run/records.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace angle_unwrap_test {

constexpr double kT = 2.0, kK = 0.2, kRudder = 0.15;  // steady turn 0.03 rad/s

// psi(t) of T r' + r = K delta from rest: K delta (t - T (1 - exp(-t / T))).
double Heading(double t) { return kK * kRudder * (t - kT * (1.0 - std::exp(-t / kT))); }

// 1000 s of a steady turn (30 rad, almost five turns), heading logged wrapped, and a
// segment column splitting it at 500 s.
Trajectory TurningRecord() {
  Trajectory data;
  data.source = "turn.csv";
  data.names = {"delta", "psi", "segment"};
  data.columns.resize(3);
  for (int k = 0; k <= 10000; ++k) {
    const double t = 0.1 * k;
    data.t.push_back(t);
    data.columns[0].push_back(kRudder);
    data.columns[1].push_back(WrapAngle(Heading(t)));
    data.columns[2].push_back(t < 500.0 ? 1 : 2);
  }
  return data;
}

ExperimentSpec Spec() {
  ExperimentSpec spec;
  spec.name = "turn";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  return spec;
}

class AngleTest : public ::testing::Test {
 protected:
  Experiment Build(const ExperimentSpec& spec, const Trajectory& data) {
    Experiment e;
    std::string error;
    EXPECT_TRUE(BuildExperiment(spec, data, model_->info(), ExperimentOptions(), &e, &error))
        << error;
    return e;
  }

  // RMSE of psi simulated with gain `k` (T and the bias at their true values).
  double HeadingRmse(const Experiment& experiment, double k) {
    std::vector<ParameterSpec> specs(3);
    const char* names[] = {"T", "K", "delta_0"};
    const double values[] = {kT, k, 0.0};
    for (int i = 0; i < 3; ++i) {
      specs[i].name = names[i];
      specs[i].start = values[i];
      specs[i].role = ParameterRole::kFixed;
    }
    std::string error;
    auto problem =
        OutputErrorProblem::Create(model_.get(), {experiment}, specs, OutputErrorOptions(), &error);
    EXPECT_NE(problem, nullptr) << error;
    std::vector<ExperimentFit> fits;
    EXPECT_TRUE(EvaluateFit(*problem, &fits, &error)) << error;
    return fits[0].channels[0].rmse;
  }

  std::unique_ptr<ModelHandle> model_ = nomoto::MakeFirstOrderHandle();
};

TEST_F(AngleTest, MeasuredHeadingIsUnwrappedWhenRead) {
  const Experiment e = Build(Spec(), TurningRecord());
  ASSERT_EQ(e.num_samples(), 10001);
  double largest_error = 0.0;
  for (int k = 0; k < e.num_samples(); ++k) {
    largest_error = std::max(largest_error, std::abs(e.samples[k].value - Heading(0.1 * k)));
  }
  EXPECT_LT(largest_error, 1e-12);
  EXPECT_GT(e.samples.back().value, 4 * 2 * M_PI);  // the turns are all there
}

TEST_F(AngleTest, HeadingTurnsOffIsScoredAsTurnsOff) {
  const Experiment e = Build(Spec(), TurningRecord());
  EXPECT_LT(HeadingRmse(e, kK), 1e-4);  // RK4 on the closed form
  // A gain that ends three whole turns further round.
  const double off = kK * (1.0 + 3 * 2 * M_PI / Heading(1000.0));
  EXPECT_GT(HeadingRmse(e, off), 8.0);  // RMSE of an error growing to 6 pi: 6 pi / sqrt(3)
  // Wrapped on request, the same error reads as at most half a turn.
  ExperimentSpec wrapped = Spec();
  wrapped.wrapped_outputs = {"psi"};
  const Experiment w = Build(wrapped, TurningRecord());
  EXPECT_LT(HeadingRmse(w, off), M_PI / std::sqrt(3.0) + 0.1);
  EXPECT_LE(std::abs(w.samples.back().value), M_PI);  // the samples stay as logged
}

// The data's own noise level of a wrapped heading (second differences, which jump by a turn
// where the log wraps) is the unwrapped heading's: the first solve under noise weights and
// the initial-state priors weigh by it.
TEST_F(AngleTest, WrappedHeadingHasTheUnwrappedNoiseLevel) {
  Trajectory data = TurningRecord();
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (double& psi : data.columns[1]) psi = WrapAngle(psi + noise(random));
  const Experiment unwrapped = Build(Spec(), data);
  ExperimentSpec spec = Spec();
  spec.wrapped_outputs = {"psi"};
  const Experiment wrapped = Build(spec, data);
  EXPECT_NEAR(unwrapped.NoiseLevel(0), 0.005, 0.0005);
  EXPECT_NEAR(wrapped.NoiseLevel(0), unwrapped.NoiseLevel(0), 1e-12);
}

// A jump between two windows (the unlogged gap between the segments of a record) is not the
// window's to resolve; inside the window it is refused, naming the times.
TEST_F(AngleTest, JumpOutsideTheWindowIsNotRefused) {
  Trajectory data = TurningRecord();
  for (size_t k = 0; k < data.t.size(); ++k) {
    if (data.t[k] >= 500.0) data.columns[1][k] = WrapAngle(data.columns[1][k] + 2.6);
  }
  ExperimentSpec before = Spec();
  before.t_end = 499.9;
  Build(before, data);
  ExperimentSpec after = Spec();
  after.t_begin = 500.0;
  Build(after, data);
  Experiment e;
  std::string error;
  EXPECT_FALSE(BuildExperiment(Spec(), data, model_->info(), ExperimentOptions(), &e, &error));
  EXPECT_NE(error.find("changes by 149 deg between t = 499.9 and 500"), std::string::npos)
      << error;
}

// The experiments cut from one record share its channels (RecordChannels): windows built
// one after another from one cache, wrapped or not, refused or not, are what building each
// alone gives, sample for sample and message for message.
TEST_F(AngleTest, WindowsSharingTheRecordsChannelsAreBuiltAsAlone) {
  Trajectory data = TurningRecord();
  for (size_t k = 0; k < data.t.size(); ++k) {
    if (data.t[k] >= 500.0) data.columns[1][k] = WrapAngle(data.columns[1][k] + 2.6);
  }
  std::vector<ExperimentSpec> specs(5, Spec());
  specs[0].t_end = 499.9;
  specs[1].t_begin = 500.0;
  specs[2].t_begin = 250.0;  // across the jump: refused
  specs[3].wrapped_outputs = {"psi"};
  specs[4].t_begin = 600.0;
  specs[4].t_end = 900.0;
  RecordChannels shared(data);
  for (const ExperimentSpec& spec : specs) {
    Experiment alone, together;
    std::string alone_error, together_error;
    const bool built =
        BuildExperiment(spec, data, model_->info(), ExperimentOptions(), &alone, &alone_error);
    EXPECT_EQ(BuildExperiment(spec, &shared, model_->info(), ExperimentOptions(), &together,
                              &together_error),
              built);
    EXPECT_EQ(together_error, alone_error);
    if (!built) continue;
    ASSERT_EQ(together.num_samples(), alone.num_samples());
    for (int k = 0; k < alone.num_samples(); ++k) {
      ASSERT_EQ(together.samples[k].value, alone.samples[k].value) << k;
    }
    EXPECT_EQ(together.node_time, alone.node_time);
    EXPECT_EQ(together.input_cache, alone.input_cache);
    EXPECT_EQ(together.initial_state, alone.initial_state);
  }
}

TEST_F(AngleTest, UnwrapAnglesTakesTheShorterWayRound) {
  std::vector<double> angles = {3.0, -3.0, 3.1, -3.1};
  const double largest = UnwrapAngles(&angles);
  EXPECT_NEAR(angles[1], 2 * M_PI - 3.0, 1e-12);
  EXPECT_NEAR(angles[3], 2 * M_PI - 3.1, 1e-12);
  EXPECT_NEAR(largest, 2 * M_PI - 6.0, 1e-12);
}

// continuation: [10] on a record split by a segment column cuts every segment into pieces.
TEST_F(AngleTest, ContinuationCutsSegmentColumnRecordsIntoPieces) {
  ExperimentSpec spec = Spec();
  spec.segments.column = "segment";
  std::vector<ExperimentSpec> whole, pieces;
  std::string error;
  ASSERT_TRUE(RecordSpecs(spec, TurningRecord(), 0.0, &whole, &error)) << error;
  ASSERT_TRUE(RecordSpecs(spec, TurningRecord(), 100.0, &pieces, &error)) << error;
  ASSERT_EQ(whole.size(), 2u);
  ASSERT_EQ(pieces.size(), 10u);
  EXPECT_EQ(pieces[0].name, "turn@1.1");
  EXPECT_EQ(pieces[5].name, "turn@2.1");
  EXPECT_DOUBLE_EQ(pieces[5].t_begin, whole[1].t_begin);
  EXPECT_DOUBLE_EQ(pieces[4].t_end, whole[0].t_end);
}

}  // namespace angle_unwrap_test
}  // namespace vesselid
