// `vesselid predict` on runs whose truth is known: the cargo ship's second-order Nomoto model
// identified from a noisy heading record predicts the 10/10 and 20/20 zigzag overshoots and
// the initial turning ability with 95 % intervals that hold the truth's figures, the ensemble
// and delta-method intervals agree, and each figure is held against its IMO criterion for the
// given L/U. The figures of the truth are computed by the same closed-loop simulation
// (PredictManoeuvres on the true parameters), independently of any run.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "engine/export/model_json.h"
#include "engine/export/run_folder_model.h"
#include "engine/export/manoeuvres.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "tests/support/run_command.h"
#include "tests/support/simulated_records.h"

namespace vesselid {
namespace manoeuvre_prediction_test {

namespace fs = std::filesystem;

// The command's output; `status` its exit status (tests/support/run_command.h).
std::string Shell(const std::string& command, int* status) {
  const testing::CommandOutcome outcome = testing::RunCommand(command);
  *status = outcome.status;
  return outcome.output;
}

// Simulates and runs configs/<name>.yaml into dir/run.
void SimulateAndRun(const std::string& name, const fs::path& dir) {
  const std::string binary = VESSELID_BINARY;
  const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/" + name + ".yaml";
  fs::remove_all(dir);
  const fs::path data = testing::SimulatedRecords(name);
  ASSERT_FALSE(data.empty()) << "vesselid simulate " << config;
  int status = 0;
  Shell(binary + " run " + config + " --data " + data.string() + " --out " +
            (dir / "run").string() + " --quiet --no-report",
        &status);
  ASSERT_EQ(status, 0);
}

TEST(ManoeuvrePrediction, CargoShipOvershootsAndTurningWithIntervalsHoldTheTruth) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_predict_cargo";
  ASSERT_NO_FATAL_FAILURE(SimulateAndRun("nomoto_cargo_noise", dir));
  int status = 0;
  // A cargo ship of 161 m at 7.7 m/s (15 kn): L/U = 20.9 s.
  const std::string output = Shell(std::string(VESSELID_BINARY) + " predict " +
                                       (dir / "run").string() + " --length 161 --speed 7.7",
                                   &status);
  ASSERT_EQ(status, 0) << output;
  std::ifstream in(dir / "run" / "predict" / "predictions.json");
  const nlohmann::json predicted = nlohmann::json::parse(in);
  EXPECT_TRUE(fs::exists(dir / "run" / "predict" / "predictions.txt"));

  // The truth's figures (configs/nomoto_cargo_noise.yaml: T1 45, T2 6, T3 10, K 0.09).
  const ModelRegistry registry = DefaultRegistry();
  IdentifiedModel truth;
  std::string error;
  const auto model =
      MakeIdentifiedModel(registry, "nomoto", {{"type", "second_order"}}, &truth, &error);
  ASSERT_NE(model, nullptr) << error;
  const std::map<std::string, double> true_values = {
      {"T1", 45.0}, {"T2", 6.0}, {"T3", 10.0}, {"K", 0.09}, {"delta_0", 0.0}};
  for (size_t i = 0; i < truth.parameters.size(); ++i) {
    truth.values[i] = true_values.at(truth.parameters[i].name);
  }
  ManoeuvreConditions conditions;
  conditions.length = 161.0;
  conditions.speed = 7.7;
  ManoeuvrePredictions true_figures;
  ASSERT_TRUE(PredictManoeuvres(truth, *model, conditions, &true_figures, &error)) << error;

  std::map<std::string, double> limit = {{"zigzag_10_10.first_overshoot", 5.0 + 0.5 * 161 / 7.7},
                                         {"zigzag_10_10.second_overshoot", 17.5 + 0.75 * 161 / 7.7},
                                         {"zigzag_20_20.first_overshoot", 25.0},
                                         {"initial_turning", 2.5}};
  ASSERT_EQ(predicted["figures"].size(), true_figures.figures.size());
  for (size_t f = 0; f < true_figures.figures.size(); ++f) {
    const nlohmann::json& p = predicted["figures"][f];
    const std::string name = p["name"];
    const double value = p["value"], low = p["ensemble_interval"][0],
                 high = p["ensemble_interval"][1];
    const double truth_value = true_figures.figures[f].value;
    std::printf("%-30s %8.4f [%8.4f, %8.4f] truth %8.4f\n", name.c_str(), value, low, high,
                truth_value);
    if (name == "pull_out.residual_rate") {
      // A course-stable ship: no yaw rate left, in every member.
      EXPECT_LT(high, 1e-3) << name;
      EXPECT_LT(truth_value, 1e-3) << name;
      continue;
    }
    EXPECT_EQ(p["ensemble_members"], 100) << name;
    EXPECT_LT(low, value) << name;
    EXPECT_GT(high, value) << name;
    // The truth within the interval (widened by 20 % for a single noise realisation).
    const double half = 0.5 * (high - low);
    EXPECT_NEAR(truth_value, 0.5 * (low + high), 1.2 * half) << name;
    EXPECT_TRUE(p["methods_agree"].get<bool>()) << name;
    if (limit.count(name)) {
      EXPECT_NEAR(p["limit"].get<double>(), limit[name], 1e-9) << name;
      EXPECT_TRUE(p["meets"].get<bool>()) << name;
    } else {
      EXPECT_TRUE(p["limit"].is_null()) << name;
    }
  }
  EXPECT_NE(output.find("met (the whole interval)"), std::string::npos) << output;
  EXPECT_NE(output.find("course-stable, with every member"), std::string::npos) << output;
  fs::remove_all(dir);
}

// The pull-out test tells the course-unstable tanker (configs/nomoto_tanker.yaml's truth, the
// n1 form with n1 < 0) by the yaw rate it keeps with the rudder at midships: the stable
// branch of n1 r + n3 r^3 = 0, r = sqrt(-n1 / n3_nd) U/L.
TEST(ManoeuvrePrediction, PullOutTellsTheUnstableTanker) {
  const ModelRegistry registry = DefaultRegistry();
  IdentifiedModel tanker;
  std::string error;
  const auto model = MakeIdentifiedModel(
      registry, "nomoto", {{"type", "norrbin_n1"}, {"length", "320"}}, &tanker, &error);
  ASSERT_NE(model, nullptr) << error;
  tanker.values = {2.2, 1.9, -0.3, 12.0, 0.0};  // T_nd, K_nd, n1, n3_nd, delta_0
  ManoeuvreConditions conditions;
  conditions.speed = 7.7;
  ManoeuvrePredictions predictions;
  ASSERT_TRUE(PredictManoeuvres(tanker, *model, conditions, &predictions, &error)) << error;
  const ManoeuvreFigure& pull_out = predictions.figures.back();
  ASSERT_EQ(pull_out.name, "pull_out.residual_rate");
  const double expected = std::sqrt(0.3 / 12.0) * 7.7 / 320.0 * 180.0 / M_PI;  // deg/s
  EXPECT_NEAR(pull_out.value, expected, 0.02 * expected);
  bool said = false;
  for (const std::string& note : predictions.notes) {
    said = said || note.find("course-unstable") != std::string::npos;
  }
  EXPECT_TRUE(said);
}

// The identified process noise flown in `predict` (process_noise.h): white noise of spectral
// density q on the yaw rate's equation, Euler-Maruyama after each RK4 step. The spread it gives
// a figure grows as sqrt(q) (four times q, twice the width) and does not depend on the
// simulation's step (the increment is sqrt(q h), not q h); the calm ensemble is untouched.
TEST(ManoeuvrePrediction, TheIdentifiedGustsWidenTheIntervalAsTheirSpectralDensityAsks) {
  const ModelRegistry registry = DefaultRegistry();
  IdentifiedModel cargo;
  std::string error;
  const auto model =
      MakeIdentifiedModel(registry, "nomoto", {{"type", "first_order"}}, &cargo, &error);
  ASSERT_NE(model, nullptr) << error;
  // T 3 s, K 0.5 1/s: a small, quick craft (short manoeuvres); 200 identical members, so the
  // spread is the gusts'.
  for (size_t i = 0; i < cargo.parameters.size(); ++i) {
    const std::string& name = cargo.parameters[i].name;
    cargo.values[i] = name == "T" ? 3.0 : name == "K" ? 0.5 : 0.0;
  }
  cargo.ensemble.assign(200, cargo.values);
  ManoeuvreConditions conditions;
  conditions.pull_out_turn = conditions.pull_out_settle = 30.0;
  auto width = [&](double q, double step, double* calm) {
    cargo.process_noise = {{"r", q, 0.0}};
    conditions.step = step;
    ManoeuvrePredictions predictions;
    EXPECT_TRUE(PredictManoeuvres(cargo, *model, conditions, &predictions, &error)) << error;
    const ManoeuvreFigure& first = predictions.figures[0];  // 10/10 first overshoot
    EXPECT_EQ(first.disturbance_members, 200);
    EXPECT_EQ(predictions.process_noise.size(), 1u);
    *calm = first.ensemble_high - first.ensemble_low;
    return first.disturbance_high - first.disturbance_low;
  };
  // q 1e-6 (rad/s)^2/s: overshoot spreads of about a degree. Each member draws the same
  // numbers for 4 q as for q (its seed is the member's), so in this nearly linear regime the
  // width doubles closely; at half the step the numbers differ, so within the quantiles' spread.
  double calm = 0.0;
  const double base = width(1e-6, 0.01, &calm);
  EXPECT_EQ(calm, 0.0);
  EXPECT_GT(base, 0.05);
  const double four = width(4e-6, 0.01, &calm), fine = width(1e-6, 0.005, &calm);
  std::printf("gust widths: q %.4g, 4 q %.4g (x%.3f), half the step %.4g (x%.3f)\n", base, four,
              four / base, fine, fine / base);
  EXPECT_NEAR(four / base, 2.0, 0.1);
  EXPECT_NEAR(fine / base, 1.0, 0.2);
  // What cannot be flown is said, not dropped: an unknown state, a spectral density that is
  // not positive, a state listed twice (a few members suffice).
  cargo.ensemble.resize(10);
  cargo.process_noise = {{"zz", 1e-8, 0.0}, {"r", -1.0, 0.0}, {"r", 1e-8, 0.0}, {"r", 2e-8, 0.0}};
  ManoeuvrePredictions edited;
  ASSERT_TRUE(PredictManoeuvres(cargo, *model, conditions, &edited, &error)) << error;
  ASSERT_EQ(edited.process_noise.size(), 1u);
  EXPECT_EQ(edited.process_noise[0].spectral_density, 1e-8);
  std::string notes;
  for (const std::string& note : edited.notes) notes += note + "\n";
  EXPECT_NE(notes.find("has no state 'zz'"), std::string::npos) << notes;
  EXPECT_NE(notes.find("positive and finite"), std::string::npos) << notes;
  EXPECT_NE(notes.find("listed twice"), std::string::npos) << notes;
  // No process noise: no third interval.
  cargo.process_noise.clear();
  ManoeuvrePredictions calm_predictions;
  ASSERT_TRUE(PredictManoeuvres(cargo, *model, conditions, &calm_predictions, &error));
  EXPECT_EQ(calm_predictions.figures[0].disturbance_members, 0);
  EXPECT_FALSE(ManoeuvresToJson(calm_predictions)["figures"][0].contains("disturbance_interval"));
}

// A rudder bias (a run's per-run delta_0 averaged into the final values) turns a course-stable
// ship the same way after a turn to either side: the pull-out's figure, half the difference of
// the two rates left, is zero and the note says course-stable, where the larger rate alone
// called it unstable.
TEST(ManoeuvrePrediction, ARudderBiasIsNoCourseInstability) {
  const ModelRegistry registry = DefaultRegistry();
  IdentifiedModel ship;
  std::string error;
  const auto model =
      MakeIdentifiedModel(registry, "nomoto", {{"type", "first_order"}}, &ship, &error);
  ASSERT_NE(model, nullptr) << error;
  for (size_t i = 0; i < ship.parameters.size(); ++i) {
    const std::string& name = ship.parameters[i].name;
    ship.values[i] = name == "T" ? 8.0 : name == "K" ? 0.15 : name == "delta_0" ? 0.01 : 0.0;
  }
  ManoeuvreConditions conditions;
  conditions.pull_out_turn = conditions.pull_out_settle = 120.0;
  ManoeuvrePredictions predictions;
  ASSERT_TRUE(PredictManoeuvres(ship, *model, conditions, &predictions, &error)) << error;
  EXPECT_LT(std::abs(predictions.figures.back().value), 1e-3);  // deg/s; the bias turns it 0.086
  bool stable = false;
  for (const std::string& note : predictions.notes) {
    stable = stable || note.find("course-stable") != std::string::npos;
  }
  EXPECT_TRUE(stable);
}

// Without L and U the turning is a time and only the 20/20 criterion applies; a model that
// needs the speed as an input asks for it; a model without a rudder is refused.
TEST(ManoeuvrePrediction, SaysWhatItCannotPredict) {
  const ModelRegistry registry = DefaultRegistry();
  IdentifiedModel cargo;
  std::string error;
  const auto model =
      MakeIdentifiedModel(registry, "nomoto", {{"type", "second_order"}}, &cargo, &error);
  ASSERT_NE(model, nullptr) << error;
  cargo.values = {45.0, 6.0, 10.0, 0.09, 0.0};
  ManoeuvrePredictions predictions;
  ASSERT_TRUE(PredictManoeuvres(cargo, *model, ManoeuvreConditions(), &predictions, &error));
  const ManoeuvreFigure& turning = predictions.figures[4];
  EXPECT_EQ(turning.name, "initial_turning_time");
  EXPECT_EQ(turning.unit, "s");
  EXPECT_GT(turning.value, 10.0);
  for (const ManoeuvreFigure& f : predictions.figures) {
    EXPECT_EQ(std::isfinite(f.limit), f.name == "zigzag_20_20.first_overshoot") << f.name;
  }
  ASSERT_FALSE(predictions.notes.empty());
  EXPECT_NE(predictions.notes.back().find("--length, --speed"), std::string::npos);

  IdentifiedModel tanker;
  const auto n1 = MakeIdentifiedModel(registry, "nomoto", {{"type", "norrbin_n1"}, {"length", "320"}},
                                    &tanker, &error);
  ASSERT_NE(n1, nullptr) << error;
  EXPECT_FALSE(PredictManoeuvres(tanker, *n1, ManoeuvreConditions(), &predictions, &error));
  EXPECT_NE(error.find("--speed"), std::string::npos) << error;

  IdentifiedModel catamaran;
  const auto six = MakeIdentifiedModel(registry, "erunsal6dof", {}, &catamaran, &error);
  ASSERT_NE(six, nullptr) << error;
  EXPECT_FALSE(PredictManoeuvres(catamaran, *six, ManoeuvreConditions(), &predictions, &error));
  EXPECT_NE(error.find("rudder input 'delta'"), std::string::npos) << error;
}

}  // namespace manoeuvre_prediction_test
}  // namespace vesselid
