// Held-out runs with their own per-experiment parameters: a first-order Nomoto model with a
// rudder bias per run, identified on zigzags flown by a second-order ship (another model)
// with a different rudder bias in every run, steering-gear lag and sensor noise. Each held-out
// run estimates its own bias with the shared T and K held; the run reports the estimate and the
// fit without it, in every output.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "engine/config/config.h"
#include "engine/report/report_html.h"
#include "engine/output/results_json.h"
#include "engine/output/results_text.h"
#include "engine/output/stage_result_archive.h"
#include "engine/run/held_out.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/finding_report.h"
#include "engine/run/pipeline.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace held_out_parameters_test {

namespace fs = std::filesystem;

constexpr double kDegree = M_PI / 180.0;
// Rudder bias of each run (deg); z4 and z5 are held out.
constexpr double kBias[] = {2.0, -1.5, 3.0, -2.5, 1.5, -3.0};

class HeldOutParametersTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per test process: ctest runs this suite's tests as parallel processes.
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_held_out_parameters_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    // Second-order ship: T1 25 s, T2 3 s, T3 6 s, K 0.08 1/s; zigzags 10/10 and 20/20.
    auto ship = nomoto::MakeSecondOrderHandle();
    for (int i = 0; i < 6; ++i) {
      nomoto::ClosedLoopOptions loop;
      loop.steering_time_constant = 2.0;
      loop.duration = 240.0;
      loop.sample_time = 0.2;
      loop.excitation.type = nomoto::Excitation::Type::kZigzag;
      loop.excitation.zigzag_rudder = (i % 2 == 0 ? 10.0 : 20.0) * kDegree;
      loop.excitation.zigzag_heading = (i % 2 == 0 ? 10.0 : 20.0) * kDegree;
      loop.heading_noise = 0.1 * kDegree;
      loop.rudder_noise = 0.1 * kDegree;
      loop.seed = 40 + i;
      Trajectory data;
      std::string error;
      ASSERT_TRUE(nomoto::SimulateClosedLoop(*ship, {25.0, 3.0, 6.0, 0.08, kBias[i] * kDegree},
                                             loop, &data, &error))
          << error;
      ASSERT_TRUE(
          WriteTrajectoryCsv((*dir_ / ("z" + std::to_string(i) + ".csv")).string(), data, &error));
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  // The stage's held-out runs start as `start` says: the tests of the per-experiment estimates
  // refit them on the whole run (the estimates are then the whole run's); the default start,
  // the measured one, is tested on its own below.
  static bool Run(const std::string& extra, RunConfig* config, RunResult* result,
                  const std::string& bias_bounds = "lower: -0.1, upper: 0.1",
                  const std::string& start = "refitted") {
    std::string text = "model: {family: nomoto, type: first_order}\nexperiments:\n";
    for (int i = 0; i < 6; ++i) {
      const std::string name = "z" + std::to_string(i);
      text += "  - {name: " + name + ", file: " + name +
              ".csv, inputs: {delta: delta}, outputs: {psi: psi}}\n";
    }
    text += R"(stages:
  - name: biased
    experiments: [z0, z1, z2, z3]
    validation: [z4, z5]
    held_out: {start: REFITTED}
    free_initial_states: [psi]
    parameters:
      T: {start: 20, lower: 1, upper: 200}
      K: {start: 0.05, lower: 0.001, upper: 1}
      delta_0: {start: 0.0, BOUNDS, role: per_experiment}
)" + extra;
    text.replace(text.find("BOUNDS"), 6, bias_bounds);
    text.replace(text.find("REFITTED"), 8, start);
    std::ofstream(*dir_ / "run.yaml") << text;
    static const ModelRegistry registry = DefaultRegistry();
    std::string error;
    if (!LoadRunConfig((*dir_ / "run.yaml").string(), "", registry, config, &error)) {
      ADD_FAILURE() << error;
      return false;
    }
    if (!Identify(*config, result, &error)) {
      ADD_FAILURE() << error;
      return false;
    }
    return true;
  }

  static fs::path* dir_;
};

fs::path* HeldOutParametersTest::dir_ = nullptr;

// A run result holding only `stage` (to compare what results.json says of it).
RunResult Single(const StageResult& stage) {
  RunResult run;
  run.stages = {stage};
  return run;
}

double FitPercent(const ExperimentFit& fit) {
  return fit.channels.empty() ? std::nan("") : fit.channels[0].fit_percent;
}

TEST_F(HeldOutParametersTest, HeldOutRunsEstimateTheirOwnBiasAndShowWhatItBuys) {
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(Run("final_validation: {held_out: {start: refitted}, experiments: [z4, z5]}\n", &config, &result));
  ASSERT_EQ(result.stages.size(), 1u);
  // "Without" holds the bias at the mean of the training runs' estimates, not at one
  // training run's value.
  double training_mean = 0.0;
  int training_runs = 0;
  for (const Estimate& e : result.stages[0].estimates) {
    if (e.kind != EstimateKind::kParameter || e.role != ParameterRole::kPerExperiment) continue;
    training_mean += e.value;
    ++training_runs;
  }
  ASSERT_GE(training_runs, 2);
  training_mean /= training_runs;
  for (const HeldOutParameters* held :
       {&result.stages[0].held_out_parameters, &result.final_held_out_parameters}) {
    const std::vector<ExperimentFit>& with = held == &result.final_held_out_parameters
                                                 ? result.final_validation
                                                 : result.stages[0].validation;
    ASSERT_TRUE(held->fitted);
    ASSERT_EQ(held->parameters, std::vector<std::string>{"delta_0"});
    ASSERT_EQ(held->estimates.size(), 2u);
    ASSERT_EQ(held->without.size(), 2u);
    ASSERT_EQ(with.size(), 2u);
    for (int k = 0; k < 2; ++k) {
      const Estimate& e = held->estimates[k];
      EXPECT_EQ(e.experiment, "z" + std::to_string(4 + k));
      EXPECT_NEAR(e.start, training_mean, 1e-12) << e.experiment;
      // Near the bias the run was flown with, although the model is not the ship's.
      EXPECT_NEAR(e.value / kDegree, kBias[4 + k], 0.3) << e.experiment;
      EXPECT_GT(e.std_error, 0.0);
      EXPECT_LT(e.std_error, 0.1 * kDegree);
      // The bias buys the fit: without it the run drifts off.
      const double fit_with = FitPercent(with[k]), fit_without = FitPercent(held->without[k]);
      EXPECT_GT(fit_with, 80.0) << e.experiment;
      EXPECT_GT(fit_with, fit_without + 20.0) << e.experiment;
    }
  }
  // The stage and its start are validated alike (each held-out run fits its bias in both):
  // the identified stage is better than its start.
  EXPECT_TRUE(result.stages[0].held_out.done);
  EXPECT_FALSE(result.stages[0].held_out.worse);

  // A checkpoint keeps them (a resumed run reports the same).
  StageResult restored;
  std::string error;
  ASSERT_TRUE(StageResultFromArchive(
      nlohmann::json::from_cbor(nlohmann::json::to_cbor(StageResultToArchive(result.stages[0]))),
      &restored, &error))
      << error;
  EXPECT_EQ(restored.held_out_parameters.estimates.size(), 2u);
  EXPECT_EQ(RunResultToJson(config, Single(restored))["stages"][0]["held_out_parameters"],
            RunResultToJson(config, Single(result.stages[0]))["stages"][0]["held_out_parameters"]);

  // The final table shows the bias as one value per run, not as held fixed.
  const FinalParameter* bias = nullptr;
  for (const FinalParameter& f : result.parameters) {
    if (f.name == "delta_0") bias = &f;
  }
  ASSERT_NE(bias, nullptr);
  EXPECT_EQ(bias->role, ParameterRole::kPerExperiment);
  EXPECT_EQ(bias->runs, 4);
  EXPECT_NEAR(bias->runs_min / kDegree, -2.5, 0.4);
  EXPECT_NEAR(bias->runs_max / kDegree, 3.0, 0.4);

  // results.json, report.txt and report.html carry it.
  const nlohmann::json j = RunResultToJson(config, result);
  for (const nlohmann::json& held :
       {j["stages"][0]["held_out_parameters"], j["final_held_out_parameters"]}) {
    ASSERT_EQ(held["per_experiment"], "fit") << j.dump(1);
    ASSERT_EQ(held["runs"].size(), 2u);
    const nlohmann::json& run = held["runs"][1];
    EXPECT_EQ(run["experiment"], "z5");
    EXPECT_NEAR(run["estimates"]["delta_0"]["value"].get<double>() / kDegree, -3.0, 0.3);
    EXPECT_TRUE(run["estimates"]["delta_0"]["std_error"].is_number());
    EXPECT_GT(run["fit_percent"]["psi"]["with"].get<double>(),
              run["fit_percent"]["psi"]["without"].get<double>());
    EXPECT_TRUE(held["mean_fit_percent"]["psi"]["with"].is_number());
  }
  const nlohmann::json& final_bias = j["parameters"][2];
  EXPECT_EQ(final_bias["name"], "delta_0");
  EXPECT_EQ(final_bias["role"], "per_experiment");
  EXPECT_EQ(final_bias["runs"]["count"], 4);

  const std::string text = RunResultToText(config, result);
  EXPECT_NE(text.find("held-out runs with their own delta_0"), std::string::npos) << text;
  EXPECT_NE(text.find("  z5: delta_0 = "), std::string::npos) << text;
  EXPECT_NE(text.find(" % without delta_0, "), std::string::npos) << text;
  EXPECT_NE(text.find("4 runs: "), std::string::npos) << text;

  // Every run is a zigzag: its figures, measured and simulated, for the four training runs,
  // the stage's two held-out runs and the final validation's two.
  ASSERT_EQ(result.zigzags.size(), 8u);
  for (const ZigzagRun& z : result.zigzags) {
    const double size =
        z.experiment == "z0" || z.experiment == "z2" || z.experiment == "z4" ? 10.0 : 20.0;
    EXPECT_NEAR(z.test.rudder / kDegree, size, 0.2) << z.experiment;
    EXPECT_NEAR(z.test.heading / kDegree, size, 0.5) << z.experiment;
    EXPECT_GT(z.measured.first_overshoot, 0.0);
    EXPECT_NEAR(z.simulated.first_overshoot / kDegree, z.measured.first_overshoot / kDegree, 1.5)
        << z.stage << " " << z.experiment;
    EXPECT_NEAR(z.simulated.period, z.measured.period, 3.0) << z.stage << " " << z.experiment;
    EXPECT_NEAR(z.simulated.time_to_first_check, z.measured.time_to_first_check, 3.0);
  }
  EXPECT_EQ(j["zigzags"].size(), 8u);
  EXPECT_TRUE(j["zigzags"][7]["measured"]["second_overshoot_deg"].is_number());
  EXPECT_NE(text.find("zigzag figures, measured / simulated"), std::string::npos);

  const std::string html = RunReportHtml(config, result);
  EXPECT_NE(html.find("<h2>Zigzag figures</h2>"), std::string::npos);
  EXPECT_NE(html.find("Per-experiment parameters of the held-out runs"), std::string::npos);
  EXPECT_NE(html.find("psi fit % without"), std::string::npos);
  EXPECT_NE(html.find("per run (4): "), std::string::npos);
  EXPECT_EQ(html.find("Held fixed in every stage"), std::string::npos);
}

// per_experiment: hold keeps them at their start: the held-out fits are those reported
// "without". With every held-out run's bias at 0, the held-out check judges the identified
// stage worse than its start (a smaller K drifts less) and sets it aside: the unfairness
// fitting the biases removes.
TEST_F(HeldOutParametersTest, HoldKeepsThemAtTheirStart) {
  RunConfig config;
  RunResult fitted, held;
  ASSERT_TRUE(Run("final_validation: {held_out: {start: refitted}, experiments: [z4, z5]}\n", &config, &fitted));
  ASSERT_TRUE(
      Run("    validation_per_experiment: hold\n"
          "final_validation: {held_out: {start: refitted}, experiments: [z4, z5], per_experiment: hold}\n",
          &config, &held));
  for (const HeldOutParameters* p :
       {&held.stages[0].held_out_parameters, &held.final_held_out_parameters}) {
    EXPECT_FALSE(p->fitted);
    EXPECT_TRUE(p->estimates.empty());
  }
  ASSERT_EQ(held.stages[0].validation.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_DOUBLE_EQ(FitPercent(held.stages[0].validation[k]),
                     FitPercent(fitted.stages[0].held_out_parameters.without[k]));
  }
  EXPECT_FALSE(fitted.stages[0].held_out.worse);
  EXPECT_TRUE(held.stages[0].held_out.worse);
  EXPECT_FALSE(held.stages[0].rejected.empty());
  EXPECT_NE(RunResultToText(config, held).find("held at the training runs' mean on the held-out runs"),
            std::string::npos);
}

// A held-out bias the bounds stop is an at_bound finding naming the run, in the stage and the
// final validation.
TEST_F(HeldOutParametersTest, HeldOutEstimateAtABoundIsAWarning) {
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(Run("final_validation: {held_out: {start: refitted}, experiments: [z4, z5]}\n", &config, &result,
                  "lower: -0.04, upper: 0.1"));
  // Per stage, the lines of delta_0's at_bound findings (the stage's own runs' values and its
  // held-out runs' fold into one per stage, every run named).
  std::map<std::string, std::string> at_bound;
  for (const Finding& f : AllFindings(result)) {
    if (f.kind != FindingKind::kAtBound || f.parameter.rfind("delta_0[", 0) != 0) continue;
    EXPECT_EQ(f.severity, FindingSeverity::kWarning);
    EXPECT_EQ(f.threshold, -0.04);
    EXPECT_NE(f.message.find("is at its lower bound -0.04"), std::string::npos) << f.message;
    at_bound[f.stage] += DescribeFinding(f);
  }
  ASSERT_EQ(at_bound.size(), 2u);
  EXPECT_NE(at_bound["biased"].find("z5"), std::string::npos) << at_bound["biased"];
  EXPECT_EQ(at_bound["biased"].find("z4"), std::string::npos) << at_bound["biased"];
  EXPECT_NE(at_bound["final"].find("experiment 'z5'"), std::string::npos) << at_bound["final"];
}

// A final validation that would fit what the last stage's validation fitted (same records,
// free states and settings, the same values) takes the stage's fits instead of fitting them
// again: they are what fitting them again gives, bit for bit. The stage's two passes (at its
// estimate and at its start) run as one batch and give what two separate calls give.
TEST_F(HeldOutParametersTest, FinalValidationReusesTheStagesWhenItIsTheSame) {
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(Run("final_validation: {held_out: {start: refitted}, experiments: [z4, z5], free_initial_states: [psi]}\n",
                  &config, &result));
  ASSERT_EQ(result.stages.size(), 1u);
  const StageResult& stage = result.stages[0];
  const StageConfig& stage_config = config.stages[0];
  const ModelHandle& model = *config.model;
  std::vector<double> values;
  for (const FinalParameter& f : result.parameters) values.push_back(f.value);
  const HeldOutPerRun per_run =
      PerRunFromStage(stage, model.info(), HeldOutPerExperiment::kFit);
  ExperimentOptions options = config.final_validation.experiment;
  if (stage.integration_step > 0.0) options.max_step = stage.integration_step;
  TrajectoryCache cache;
  std::vector<ExperimentFit> fits;
  HeldOutParameters parameters;
  std::vector<ResidualAnalysis> residuals;
  std::string error;
  HeldOutStart refitted;
  refitted.mode = HeldOutStart::Mode::kRefitted;
  ASSERT_TRUE(SimulateHeldOut(config, model, {"z4", "z5"}, options, {"psi"}, {}, values, &cache,
                              &fits, &error, per_run, &parameters, &residuals, refitted))
      << error;
  auto same_fits = [](const std::vector<ExperimentFit>& a, const std::vector<ExperimentFit>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].experiment, b[k].experiment);
      ASSERT_EQ(a[k].channels.size(), b[k].channels.size());
      for (size_t c = 0; c < a[k].channels.size(); ++c) {
        EXPECT_EQ(a[k].channels[c].mae, b[k].channels[c].mae);
        EXPECT_EQ(a[k].channels[c].fit_percent, b[k].channels[c].fit_percent);
      }
    }
  };
  same_fits(result.final_validation, fits);
  same_fits(result.final_held_out_parameters.without, parameters.without);
  ASSERT_EQ(result.final_held_out_parameters.estimates.size(), parameters.estimates.size());
  for (size_t k = 0; k < parameters.estimates.size(); ++k) {
    EXPECT_EQ(result.final_held_out_parameters.estimates[k].value, parameters.estimates[k].value);
    EXPECT_EQ(result.final_held_out_parameters.estimates[k].std_error,
              parameters.estimates[k].std_error);
  }
  EXPECT_EQ(result.final_validation_residuals.size(), residuals.size());
  // Without the stage's free initial heading the final validation is another one: fitted.
  RunConfig other_config;
  RunResult other;
  ASSERT_TRUE(Run("final_validation: {held_out: {start: refitted}, experiments: [z4, z5]}\n", &other_config, &other));
  EXPECT_EQ(other.stages[0].validation[0].channels[0].mae, stage.validation[0].channels[0].mae);
  EXPECT_NE(other.final_validation[0].channels[0].mae, stage.validation[0].channels[0].mae);

  // The stage's batch of two passes against one call per pass, on one thread and on two.
  std::vector<double> start_values(values.size());
  for (size_t i = 0; i < values.size(); ++i) start_values[i] = 0.8 * values[i];
  for (int threads : {1, 2}) {
    LocalSolveOptions local = stage_config.options.local;
    local.num_threads = threads;
    std::vector<ExperimentFit> at_values, at_start, single_values, single_start;
    HeldOutParameters batch_parameters;
    ASSERT_TRUE(SimulateHeldOutPasses(
        config, model, {"z4", "z5"}, options, {"psi"}, local,
        {{&values, &at_values, &batch_parameters}, {&start_values, &at_start}}, &cache, &error,
        per_run, refitted))
        << error;
    ASSERT_TRUE(SimulateHeldOut(config, model, {"z4", "z5"}, options, {"psi"}, local, values,
                                &cache, &single_values, &error, per_run, nullptr, nullptr,
                                refitted));
    ASSERT_TRUE(SimulateHeldOut(config, model, {"z4", "z5"}, options, {"psi"}, local,
                                start_values, &cache, &single_start, &error, per_run, nullptr,
                                nullptr, refitted));
    same_fits(at_values, single_values);
    same_fits(at_start, single_start);
    same_fits(batch_parameters.without, parameters.without);
    // The start's fits move off the data: the two passes are not the same fits.
    EXPECT_NE(at_values[0].channels[0].mae, at_start[0].channels[0].mae);
  }
}

// The default: held-out runs are predicted from their measured start. The heading is
// measured and starts at its measurement; the run's bias is estimated on a burn-in of a tenth
// of the run (24 s), which is traced but not scored; the report says so; no refitted start, so
// no implausible_start finding.
TEST_F(HeldOutParametersTest, MeasuredStartPredictsAfterABurnIn) {
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(Run("final_validation: {experiments: [z4, z5], free_initial_states: [psi, r]}\n",
                  &config, &result, "lower: -0.1, upper: 0.1", "measured"));
  for (const std::vector<ExperimentFit>* fits :
       {&result.stages[0].validation, &result.final_validation}) {
    ASSERT_EQ(fits->size(), 2u);
    for (const ExperimentFit& fit : *fits) {
      ASSERT_FALSE(fit.diverged) << fit.message;
      EXPECT_EQ(fit.start.mode, "measured");
      EXPECT_NEAR(fit.start.burn_in, 24.0, 0.3) << fit.experiment;
      EXPECT_TRUE(fit.start.offsets.empty());
      // psi is measured, so never estimated; the bias is (and r, where listed free).
      const std::vector<std::string>& estimated = fit.start.estimated;
      EXPECT_EQ(std::count(estimated.begin(), estimated.end(), "psi"), 0);
      // The stage's runs estimate their bias; the final validation lists r free.
      const bool final = fits == &result.final_validation;
      if (!final) {
        EXPECT_EQ(std::count(estimated.begin(), estimated.end(), "delta_0"), 1);
      }
      EXPECT_EQ(std::count(estimated.begin(), estimated.end(), "r"), final ? 1 : 0);
      // The trace starts at the record's start, at the measured heading; the scored samples
      // are those after the burn-in.
      ASSERT_FALSE(fit.trace.t.empty());
      EXPECT_EQ(fit.trace.t.front(), 0.0);
      const int measured = fit.trace.Find("psi_measured"), simulated = fit.trace.Find("psi_simulated");
      ASSERT_GE(measured, 0);
      EXPECT_EQ(fit.trace.columns[simulated].front(), fit.trace.columns[measured].front());
      ASSERT_EQ(fit.channels.size(), 1u);
      int after = 0;
      for (double t : fit.trace.t) after += t > fit.start.burn_in + 1e-9;
      EXPECT_EQ(fit.channels[0].samples, after);
    }
  }
  for (const Finding& f : AllFindings(result)) EXPECT_NE(f.kind, FindingKind::kImplausibleStart);
  const nlohmann::json j = RunResultToJson(config, result);
  EXPECT_EQ(j["final_validation"]["start"]["z4"]["mode"], "measured");
  EXPECT_NEAR(j["final_validation"]["start"]["z5"]["burn_in_s"].get<double>(), 24.0, 0.3);
  const std::string text = RunResultToText(config, result);
  EXPECT_NE(text.find("local validation: Held-out runs are predicted from their measured "
                      "start; delta_0 estimated on a burn-in of 24 s"),
            std::string::npos)
      << text;
}

}  // namespace held_out_parameters_test
}  // namespace vesselid
