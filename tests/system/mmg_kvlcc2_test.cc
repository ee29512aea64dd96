// The shipped KVLCC2 campaign (configs/mmg_kvlcc2.yaml) end to end through the command line:
// the MMG model identified from free-running zigzags (positions, heading, speed; a rudder
// bias per run, a slow disturbance and a rudder rate limit the model does not have), then
// held-out zigzags and 35 deg turning circles predicted. What a user of the model needs: the
// turning circle's advance and tactical diameter within 5 %, the held-out zigzags' heading
// at >= 60 % fit from their measured start, the linear yaw derivatives close to the captive-test
// truth.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace mmg_kvlcc2_test {

using nlohmann::json;
namespace fs = std::filesystem;

// One case: simulating and running the campaign is what costs (18 s), and ctest runs every
// case in a process of its own.
TEST(MmgKvlcc2, ZigzagsPredictTheTurningCirclesAndHeldOutRuns) {
  const fs::path out =
      fs::temp_directory_path() / ("vesselid_mmg_kvlcc2_" + std::to_string(::getpid()));
  testing::SimulateAndRunInto("mmg_kvlcc2", out);
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
  std::ifstream in(out / "results.json");
  const json results = json::parse(in);
  std::string reports;
  for (const char* file : {"report.txt", "report.html"}) {
    std::ifstream report(out / file);
    reports.append(std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>());
  }
  // The same final validation with starts refitted on the whole run (what the shipped config
  // did before held-out runs became predictions): the refitted headings lie many noise SDs
  // from the measured ones, and each such run is an implausible_start finding with both fits.
  std::ifstream shipped(std::string(VESSELID_SOURCE_DIR) + "/configs/mmg_kvlcc2.yaml");
  std::string config((std::istreambuf_iterator<char>(shipped)), std::istreambuf_iterator<char>());
  const std::string final_line = "final_validation: {experiments: held_out,";
  ASSERT_NE(config.find(final_line), std::string::npos);
  config.replace(config.find(final_line), final_line.size(),
                 final_line + " held_out: {start: refitted},");
  // These runs are about the held-out starts: the input noise's refits (uncertainty) left out.
  const std::string stage_line = "  - name: output_error\n";
  ASSERT_NE(config.find(stage_line), std::string::npos);
  config.replace(config.find(stage_line), stage_line.size(),
                 stage_line + "    uncertainty: {input_noise: off}\n");
  std::ofstream(out / "refitted.yaml") << config;
  const std::string refit = std::string(VESSELID_BINARY) + " run " + (out / "refitted.yaml").string() +
                            " --data " + out.string() + " --out " + (out / "refitted").string() +
                            " --quiet --no-report > /dev/null";
  ASSERT_EQ(std::system(refit.c_str()), 0) << refit;
  std::ifstream refitted_in(out / "refitted" / "results.json");
  const json refitted = json::parse(refitted_in);
  // And with no initial state free: the held-out runs start where the stages would (u = 0,
  // the ship at rest) and estimate only their rudder bias on the burn-in. Each run is
  // simulated (before: "derivative by delta_0 not finite" in every run, from U = sqrt(u^2 +
  // v^2) and atan2(-v, u) at rest).
  std::string no_free = config;
  const std::string refitted_line = final_line + " held_out: {start: refitted},";
  no_free.replace(no_free.find(refitted_line), std::string::npos,
                  "final_validation: {experiments: held_out}\n");
  std::ofstream(out / "no_free.yaml") << no_free;
  const std::string run_no_free = std::string(VESSELID_BINARY) + " run " +
                                  (out / "no_free.yaml").string() + " --data " + out.string() +
                                  " --out " + (out / "no_free").string() + " --quiet --no-report > /dev/null";
  ASSERT_EQ(std::system(run_no_free.c_str()), 0) << run_no_free;
  std::ifstream no_free_in(out / "no_free" / "results.json");
  const json without_states = json::parse(no_free_in);
  fs::remove_all(out);
  EXPECT_FALSE(without_states["final_validation"].contains("diverged"))
      << without_states["final_validation"]["diverged"].dump();
  EXPECT_EQ(without_states["final_validation"]["runs"]["rows"].size(), 6u);
  for (const auto& [run, start] : without_states["final_validation"]["start"].items()) {
    EXPECT_EQ(start["estimated"], json::array({"delta_0"})) << run;
  }
  int implausible = 0;
  for (const json& f : refitted["findings"]) {
    if (f["kind"] != "implausible_start") continue;
    implausible += f.value("count", 1);  // runs alike fold into one finding
    EXPECT_EQ(f["stage"], "final");
    EXPECT_NE(f["message"].get<std::string>().find("from the measured start"), std::string::npos);
  }
  EXPECT_GE(implausible, 4);
  for (const auto& [run, start] : refitted["final_validation"]["start"].items()) {
    EXPECT_EQ(start["mode"], "refitted") << run;
    EXPECT_TRUE(start["measured_start"]["psi"]["fit_percent"].is_number()) << run;
    EXPECT_FALSE(start["refitted_offsets"].empty()) << run;
  }
  // From the measured start (the shipped config): no such finding, the burn-in reported.
  for (const json& f : results["findings"]) EXPECT_NE(f["kind"], "implausible_start");
  for (const auto& [run, start] : results["final_validation"]["start"].items()) {
    EXPECT_EQ(start["mode"], "measured") << run;
    EXPECT_GT(start["burn_in_s"].get<double>(), 8.9) << run;
    EXPECT_LT(start["burn_in_s"].get<double>(), 15.1) << run;
  }
  EXPECT_NE(reports.find("Held-out runs are predicted from their measured start"),
            std::string::npos);

  // The held-out 35 deg turning circles: advance and tactical diameter within 5 %.
  ASSERT_TRUE(results.contains("turning_circles"));
  int final_runs = 0;
  for (const json& run : results["turning_circles"]) {
    if (run["stage"] != "final") continue;
    ++final_runs;
    EXPECT_TRUE(run["held_out"].get<bool>());
    EXPECT_NEAR(run["rudder_deg"].get<double>(), 35.0, 1.0);
    for (const char* figure : {"advance", "tactical_diameter"}) {
      // The truth's KVLCC2 turns with an advance and tactical diameter of about 3.1 L.
      const double measured = run["measured"][figure].get<double>();
      EXPECT_GT(measured, 2.8 * 7.0) << run["experiment"] << " " << figure;
      EXPECT_LT(measured, 3.5 * 7.0) << run["experiment"] << " " << figure;
      EXPECT_LT(std::abs(run["error_percent"][figure].get<double>()), 5.0)
          << run["experiment"] << " " << figure;
    }
  }
  EXPECT_EQ(final_runs, 2);
  EXPECT_NE(reports.find("turning circles, measured / simulated"), std::string::npos);
  EXPECT_NE(reports.find("<h2>Turning circles</h2>"), std::string::npos);

  // The held-out zigzags' heading predicted from the measured start at >= 60 % fit (64-99 %:
  // each run's rudder bias and the unmodelled slow disturbance are known only from its first
  // 9-11 s; refitted on the whole run, as before, they were 98-99 %).
  int zigzags = 0;
  for (const json& row : results["final_validation"]["runs"]["rows"]) {
    const std::string run = row["run"];
    if (run.rfind("zz", 0) != 0) continue;
    ++zigzags;
    EXPECT_GE(row["outputs"]["psi"]["fit_percent"].get<double>(), 60.0) << run;
  }
  EXPECT_EQ(zigzags, 4);

  // The linear yaw derivatives close to Yasukawa & Yoshimura's (Table 3).
  auto value = [&](const std::string& name) {
    for (const json& p : results["parameters"]) {
      if (p["name"] == name) return p["value"].get<double>();
    }
    ADD_FAILURE() << name << " not reported";
    return std::nan("");
  };
  EXPECT_NEAR(value("N_v"), -0.137, 0.05 * 0.137);
  EXPECT_NEAR(value("N_r"), -0.049, 0.05 * 0.049);
  EXPECT_NEAR(value("Y_v"), -0.315, 0.15 * 0.315);
}

}  // namespace mmg_kvlcc2_test
}  // namespace vesselid
