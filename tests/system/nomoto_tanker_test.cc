// The shipped tanker campaign (configs/nomoto_tanker.yaml) end to end through the command
// line: a course-unstable Norrbin ship flying zigzags at two speeds, a rudder bias per run,
// heading and rudder logged in degrees, with a rudder rate limit, a slow yaw disturbance and
// a quantised compass the identified model does not have. Least squares with one bias per
// run, then output error in the n1-form with the speed input; five runs held out.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "engine/output/held_out_zigzags.h"
#include "engine/output/run_document.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/findings.h"
#include "tests/support/shipped_config.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace nomoto_tanker_test {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr double kDegree = M_PI / 180.0;

// The campaign is simulated and run once per process (ctest runs each case in its own, in
// parallel: the folder carries the process id); a failure there fails every case.
class NomotoTanker : public ::testing::Test {
 protected:
  void SetUp() override {
    if (results_ == nullptr) Load();
    ASSERT_NE(results_, nullptr) << "the campaign did not run";
  }
  static void Load() {
    const fs::path out =
        fs::temp_directory_path() / ("vesselid_nomoto_tanker_" + std::to_string(::getpid()));
    testing::SimulateAndRunInto("nomoto_tanker", out);  // both commands exit 0
    if (::testing::Test::HasFatalFailure()) return;
    std::ifstream in(out / "results.json");
    json results = json::parse(in);
    RunDocument document;
    std::string error;
    ASSERT_TRUE(ReadRunDocument(out.string(), &document, &error)) << error;
    zigzags_ = new std::vector<ZigzagEntry>(document.zigzags);
    reports_ = new std::string;
    for (const char* file : {"report.txt", "report.html"}) {
      std::ifstream report(out / file);
      reports_->append(std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>());
    }
    fs::remove_all(out);
    const YAML::Node config =
        YAML::LoadFile(std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml");
    truth_ = new std::map<std::string, double>;
    for (const auto& item : config["simulation"]["truth"]) {
      (*truth_)[item.first.as<std::string>()] = item.second.as<double>();
    }
    biases_ = new std::map<std::string, double>;
    for (const YAML::Node& run : config["simulation"]["experiments"]) {
      std::string name = run["file"].as<std::string>();
      name = name.substr(0, name.find('.'));
      (*biases_)[name] = run["rudder_bias_deg"].as<double>() * kDegree;
    }
    for (const YAML::Node& stage : config["stages"]) {
      if (!stage["validation"]) continue;
      const YAML::Node v = stage["validation"];  // a list, or the name of a set
      held_out_ = new std::vector<std::string>(
          (v.IsScalar() ? config["sets"][v.as<std::string>()] : v).as<std::vector<std::string>>());
      held_T_ = stage["parameters"]["T_nd"] ? stage["parameters"]["T_nd"]["start"].as<double>()
                                            : 2.5;  // the model's default, held
    }
    results_ = new json(std::move(results));
  }

  // A stage's estimates by name.
  static std::map<std::string, json> Estimates(const json& stage) {
    std::map<std::string, json> estimates;
    for (const json& e : stage["estimates"]) estimates[e["name"].get<std::string>()] = e;
    return estimates;
  }
  // The truth in the scale the held T_nd sets: the data determine K/T, n1/T, n3/T.
  static double Scaled(const std::string& name) {
    return truth_->at(name) * held_T_ / truth_->at("T_nd");
  }

  static json* results_;
  static std::vector<ZigzagEntry>* zigzags_;  // as the codec reads them (run_document.h)
  static std::string* reports_;  // report.txt and report.html
  static std::map<std::string, double>* truth_;
  static std::map<std::string, double>* biases_;  // per run [rad]
  static std::vector<std::string>* held_out_;
  static double held_T_;
};

json* NomotoTanker::results_ = nullptr;
std::vector<ZigzagEntry>* NomotoTanker::zigzags_ = nullptr;
std::string* NomotoTanker::reports_ = nullptr;
std::map<std::string, double>* NomotoTanker::truth_ = nullptr;
std::map<std::string, double>* NomotoTanker::biases_ = nullptr;
std::vector<std::string>* NomotoTanker::held_out_ = nullptr;
double NomotoTanker::held_T_ = 0.0;

// The output-error stage finds the ship course-unstable: n1 < 0 and within 3 standard errors
// of the truth, K and n3 within 5 %, T_nd held where configured.
TEST_F(NomotoTanker, OutputErrorFindsTheShipCourseUnstable) {
  const json& stage = (*results_)["stages"][1];
  ASSERT_EQ(stage["name"], "output_error");
  auto estimates = Estimates(stage);
  ASSERT_TRUE(estimates.count("n1"));
  const double n1 = estimates["n1"]["value"].get<double>();
  const double se = estimates["n1"]["std_error"].get<double>();
  EXPECT_LT(n1, 0.0);
  EXPECT_LT(n1 + 3 * se, 0.0) << "the sign of n1 is determined";
  EXPECT_LT(std::abs(n1 - Scaled("n1")), 3 * se)
      << n1 << " +- " << se << ", truth " << Scaled("n1");
  // K and n3 absorb a little of what the model lacks (rate limit, disturbance, compass
  // steps: 0.6 % here, tens of their standard errors): sane, not within 3 SE.
  for (const char* name : {"K_nd", "n3_nd"}) {
    const double value = estimates[name]["value"].get<double>();
    EXPECT_LT(std::abs(value / Scaled(name) - 1), 0.05) << name << " " << value;
  }
  EXPECT_DOUBLE_EQ(estimates["T_nd"]["value"].get<double>(), held_T_);
}

// The least-squares stage estimates one rudder bias per training run (reported per run, as
// output error reports them), already with n1 < 0; output error starts each run's bias there.
TEST_F(NomotoTanker, LeastSquaresEstimatesOneBiasPerRunAndStartsTheRefinement) {
  const json& ls = (*results_)["stages"][0];
  const json& oe = (*results_)["stages"][1];
  auto ls_estimates = Estimates(ls);
  auto oe_estimates = Estimates(oe);
  EXPECT_LT(ls_estimates["n1"]["value"].get<double>(), 0.0);
  int runs = 0;
  for (const auto& [run, bias] : *biases_) {
    const std::string name = "delta_0[" + run + "]";
    const bool held = std::find(held_out_->begin(), held_out_->end(), run) != held_out_->end();
    EXPECT_EQ(ls_estimates.count(name), held ? 0u : 1u) << name;
    if (held) continue;
    ++runs;
    const json& e = ls_estimates[name];
    EXPECT_EQ(e["experiment"], run);
    EXPECT_EQ(e["role"], "per_experiment");
    EXPECT_LT(std::abs(e["value"].get<double>() - bias), 0.5 * kDegree) << name;
    EXPECT_GT(e["std_error"].get<double>(), 0.0) << name;
    const json& refined = oe_estimates[name];
    EXPECT_DOUBLE_EQ(refined["start"].get<double>(), e["value"].get<double>()) << name;
    EXPECT_LT(std::abs(refined["value"].get<double>() - bias), 0.3 * kDegree) << name;
  }
  EXPECT_EQ(runs, 8);
}

// Acceptance (issue 20, as held-out runs are now predictions): each held-out run starts from
// its measured heading, its yaw rate and its own bias are estimated on the first tenth of the
// run (70-130 s, not scored), and the rest is predicted. The bias is found within 0.5 deg
// (before, refitted on the whole run: 0.2 deg), and every run's heading is predicted >= 50 %
// (55-92 %; refitted on the whole run they were >= 80 %); held at the training runs' mean, the
// bias leaves four of five runs below 0 %.
TEST_F(NomotoTanker, HeldOutHeadingPredictedFromMeasuredStartAtLeast50Percent) {
  const json& results = *results_;
  ASSERT_TRUE(results.contains("final_held_out_parameters"));
  ASSERT_TRUE(results["final_held_out_parameters"].contains("runs"));
  std::map<std::string, double> fit;
  for (const json& run : results["final_held_out_parameters"]["runs"]) {
    fit[run["experiment"].get<std::string>()] = run["fit_percent"]["psi"]["with"].get<double>();
    const std::string name = run["experiment"].get<std::string>();
    ASSERT_TRUE(run["estimates"].contains("delta_0")) << name;
    EXPECT_NEAR(run["estimates"]["delta_0"]["value"].get<double>(), biases_->at(name),
                0.5 * kDegree)
        << name;
  }
  for (const std::string& run : *held_out_) {
    ASSERT_TRUE(fit.count(run)) << run;
    EXPECT_GE(fit[run], 50.0) << run;
  }
  for (const json& m : results["final_validation"]["metrics"]) {
    if (m["output"] == "psi") {
      EXPECT_GE(m["fit_percent"].get<double>(), 50.0) << m["experiment"];
    }
  }
}

}  // namespace nomoto_tanker_test
}  // namespace vesselid

namespace vesselid {
namespace nomoto_tanker_test {

// The real-like campaign fits well (heading fits of 76-99 %), but its records carry what the
// model lacks (a slow yaw disturbance, a rate-limited gear): the output-error stage's
// residuals keep a lag-1 of 0.89-0.98 at up to 8 x the compass's noise level, which no noise
// gives. Flown from their measured starts, the held-out zigzags drift with the disturbance
// far beyond what the fit and its intervals explain (held_out_beyond_band). Those warnings
// make the verdict doubtful; nothing fails.
TEST_F(NomotoTanker, WhatTheModelLacksIsAWarning) {
  EXPECT_EQ((*results_)["verdict"], "doubtful") << testing::JsonFindingsText(*results_);
  int coloured = 0, beyond_band = 0;
  for (const json& f : testing::JsonFindings(*results_)) {
    EXPECT_NE(f["severity"], "failure") << f.dump();
    if (f["severity"] != "warning") continue;
    if (f["kind"] == "held_out_beyond_band") {
      ++beyond_band;
      continue;
    }
    ++coloured;
    EXPECT_EQ(f["kind"], "coloured_residuals") << f.dump();
    EXPECT_NE(f["message"].get<std::string>().find("the structure is strong"), std::string::npos);
  }
  EXPECT_GE(coloured, 1);
  EXPECT_GE(beyond_band, 1);
}

}  // namespace nomoto_tanker_test
}  // namespace vesselid

namespace vesselid {
namespace nomoto_tanker_test {

// The check of the held-out zigzags (report.txt, report.html, `vesselid predict`): the first
// overshoot's 95 % prediction interval (the run's simulation of the held-out record plus the
// model's error on the eight training zigzags) covers the measured overshoot in at least 4 of the 5
// held-out runs.
TEST_F(NomotoTanker, HeldOutFirstOvershootIntervalCoversTheMeasurement) {
  const HeldOutZigzagCheck check = CheckHeldOutZigzags(*zigzags_);
  std::printf("%s", HeldOutZigzagsText(check).c_str());
  ASSERT_EQ(check.errors.size(), 2u) << check.note;
  EXPECT_EQ(check.errors[0].runs, 8);
  int rows = 0, covered = 0;
  for (const HeldOutZigzag& row : check.rows) {
    if (row.figure != "first_overshoot") continue;
    ++rows;
    covered += row.covered ? 1 : 0;
    EXPECT_LT(row.high - row.low, 5.0) << row.experiment << ": an interval too wide to say much";
  }
  EXPECT_EQ(rows, static_cast<int>(held_out_->size()));
  EXPECT_GE(covered, 4);
  // Both reports show it: report.txt's line and report.html's sentence.
  const std::string says =
      "covers " + std::to_string(covered) + " of " + std::to_string(rows) + " held-out runs";
  size_t count = 0;
  for (size_t at = reports_->find(says); at != std::string::npos;
       at = reports_->find(says, at + 1)) {
    ++count;
  }
  EXPECT_GE(count, 2u) << says;  // once in each (twice each where the overshoots tally alike)
  EXPECT_NE(reports_->find("first_overshoot: the interval " + says), std::string::npos);
  EXPECT_NE(reports_->find("<h3>Held-out zigzags, measured against predicted</h3>"),
            std::string::npos);
}

// The held-out zigzags re-flown in closed loop from their measured starts
// (run/zigzag_reflight.h: the rudder reversed where the model's own heading reaches the check,
// the gear at the rate the log shows): results.json gives each one's re-flown figures beside
// the open-loop ones, report.txt a line; training runs are not re-flown.
TEST_F(NomotoTanker, HeldOutZigzagsAreReflownInClosedLoop) {
  int reflown = 0;
  for (const json& z : (*results_)["zigzags"]) {
    if (!z["held_out"].get<bool>()) {
      EXPECT_FALSE(z.contains("reflown")) << z.dump();
      continue;
    }
    ASSERT_TRUE(z.contains("reflown")) << z.dump();
    EXPECT_TRUE(z["reflown"]["first_overshoot_deg"].is_number()) << z.dump();
    std::printf("%s %s: first overshoot measured %s, open loop %s, re-flown %s deg\n",
                z["stage"].get<std::string>().c_str(), z["experiment"].get<std::string>().c_str(),
                z["measured"]["first_overshoot_deg"].dump().c_str(),
                z["simulated"]["first_overshoot_deg"].dump().c_str(),
                z["reflown"]["first_overshoot_deg"].dump().c_str());
    ++reflown;
  }
  EXPECT_GE(reflown, static_cast<int>(held_out_->size()));
  EXPECT_NE(reports_->find("re-flown"), std::string::npos);
}

}  // namespace nomoto_tanker_test
}  // namespace vesselid
