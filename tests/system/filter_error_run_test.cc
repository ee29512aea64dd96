// The filter-error method as the command line runs it (stage key `noise:`, docs/models.md
// "Disturbance models"), on the patrol vessel's multi-sine record whose logged rudder carries
// 0.1 deg of noise: output error's heading residuals are then coloured (the rudder's noise
// integrated; residual_whiteness_test.cc). With process noise on the rudder's equation the
// filter's innovations are white, the run names the disturbance (disturbance_model), reports
// its parameters as estimates of kind noise and is not called doubtful for the colour. `auto`
// picks a disturbance model by BIC and names every candidate. Keys: noise, method, angles,
// measurement (white, ar1: type, sigma, tau, white), process, wave (omega, zeta, sigma), bias
// (q, initial_sd), prediction_steps, gain.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/findings.h"

namespace vesselid {
namespace filter_error_run_test {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Config(const std::string& noise) {
  return R"(description: patrol vessel, multi-sine, noisy rudder
model: {family: nomoto, type: second_order}
simulation:
  truth: {T1: 2.0875, T2: 0.3179, T3: 0.1830, K: -0.1724}
  steering_gear: {Tm: 1.0, kp: 0.7, rudder_limit_deg: 35}
  sample_time: 0.1
  experiments:
    - file: multisine.csv
      duration: 600
      excitation: {type: multisine, amplitude_deg: 20, periods: [60, 30, 15, 7.5, 4]}
      noise: {rudder_deg: 0.1, heading_deg: 0.1}
      seed: 12
experiments:
  - name: multisine
    file: multisine.csv
    inputs: {delta: delta}
    outputs: {psi: psi}
stages:
  - name: multisine
    experiments: [multisine]
    parameters:
      T1: {start: 2.5, lower: 0.01, upper: 20.0}
      T2: {start: 0.26, lower: 0.01, upper: 20.0}
      T3: {start: 0.22, lower: 0.0, upper: 5.0}
      K: {start: -0.2, lower: -2.0, upper: -0.001}
    noise: )" + noise + "\n";
}

struct CommandRun {
  int status = -1;
  json results;
  std::string report, stderr_text;
};

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

CommandRun SimulateAndRun(const std::string& name, const std::string& noise) {
  const fs::path dir = fs::temp_directory_path() / ("vesselid_filter_error_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path config = dir / "config.yaml";
  std::ofstream(config) << Config(noise);
  const std::string binary = VESSELID_BINARY;
  const std::string simulate =
      binary + " simulate " + config.string() + " --out " + dir.string() + " > /dev/null";
  const std::string run = binary + " run " + config.string() + " --data " + dir.string() +
                          " --out " + (dir / "out").string() + " --quiet --no-report > /dev/null 2> " +
                          (dir / "stderr.txt").string();
  CommandRun result;
  EXPECT_EQ(std::system(simulate.c_str()), 0) << simulate;
  result.status = std::system(run.c_str());
  result.results = json::parse(ReadText(dir / "out" / "results.json"), nullptr, false);
  result.report = ReadText(dir / "out" / "report.txt");
  result.stderr_text = ReadText(dir / "stderr.txt");
  fs::remove_all(dir);
  return result;
}

const json* EstimateNamed(const json& results, const std::string& name) {
  for (const json& e : results["stages"][0]["estimates"]) {
    if (e["name"] == name) return &e;
  }
  return nullptr;
}

TEST(FilterErrorRun, ProcessNoiseOnTheRuddersEquationWhitensTheInnovations) {
  const CommandRun run = SimulateAndRun(
      "process", "{method: filter_error, angles: deg, measurement: {psi: {type: white, sigma: 0.1}}, "
                 "process: {xi2: auto}, prediction_steps: 5, gain: auto}");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  ASSERT_TRUE(run.results.is_object());
  const json* q = EstimateNamed(run.results, "q.process.xi2");
  ASSERT_NE(q, nullptr) << run.results["stages"][0]["estimates"].dump();
  EXPECT_EQ((*q)["kind"], "noise");
  EXPECT_GT((*q)["value"].get<double>(), 0.0);
  const json* sigma = EstimateNamed(run.results, "sigma.white.psi");
  ASSERT_NE(sigma, nullptr);
  EXPECT_NEAR((*sigma)["value"].get<double>(), 0.1 * M_PI / 180.0, 0.03 * M_PI / 180.0);
  const std::vector<json> named =
      testing::JsonFindingsOf(run.results, "disturbance_model", "process noise on xi2");
  ASSERT_EQ(named.size(), 1u) << testing::JsonFindingsText(run.results);
  EXPECT_NE(named[0]["message"].get<std::string>().find("psi white in 1 of 1"), std::string::npos)
      << named[0]["message"];
  EXPECT_TRUE(testing::JsonFindingsOf(run.results, "coloured_residuals", "").empty())
      << testing::JsonFindingsText(run.results);
  const json& a = run.results["stages"][0]["residual_analysis"][0];
  EXPECT_TRUE(a["white"].get<bool>()) << a.dump();
  // The ship's parameters near the truth (T1 2.09, K -0.172).
  EXPECT_NEAR((*EstimateNamed(run.results, "K"))["value"].get<double>(), -0.1724, 0.02);
}

TEST(FilterErrorRun, AutoNamesEveryCandidateAndKeepsTheBest) {
  const CommandRun run = SimulateAndRun("auto", "{method: auto}");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::string notes = run.results["stages"][0]["notes"].dump();
  EXPECT_NE(notes.find("noise auto: BIC"), std::string::npos) << notes;
  EXPECT_NE(notes.find("output_error"), std::string::npos) << notes;
  EXPECT_NE(notes.find("process(xi2)"), std::string::npos) << notes;
  EXPECT_NE(notes.find("chosen"), std::string::npos) << notes;
  EXPECT_NE(notes.find("output error's estimates were"), std::string::npos) << notes;
  EXPECT_NE(EstimateNamed(run.results, "q.process.xi2"), nullptr) << notes;
}

TEST(FilterErrorRun, UnknownOutputsStatesAndValuesAreRefusedWithTheKey) {
  for (const auto& [noise, says] : std::vector<std::pair<std::string, std::string>>{
           {"{measurement: {r2: white}}", "r2"},
           {"{process: {nope: auto}}", "process.nope: unknown key (allowed: psi, xi1, xi2)"},
           {"{measurement: {psi: {type: pink}}}", "unknown measurement noise 'pink'"},
           {"{wave: {psi: {zeta: 1.5}}}", "must be in (0, 1)"},
           {"{bias: {psi: {q: -1, initial_sd: 1}}}", "must be > 0"},
           {"{method: sometimes}", "unknown method 'sometimes'"},
           {"{prediction_steps: 0}", "must be >= 1"},
           {"{gain: sometimes}", "expected auto or time_varying"},
           {"{measurement: {psi: {type: ar1, sigma: 0, tau: 1, white: true}}}", "must be > 0"},
           {"{wave: {psi: {omega: -1, sigma: 1}}}", "must be > 0"}}) {
    const fs::path dir = fs::temp_directory_path() / "vesselid_filter_error_refused";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "config.yaml") << Config(noise);
    const std::string command = std::string(VESSELID_BINARY) + " run " +
                                (dir / "config.yaml").string() + " --out " +
                                (dir / "out").string() + " > " +
                                (dir / "out.txt").string() + " 2>&1";
    EXPECT_NE(std::system(command.c_str()), 0) << noise;
    const std::string text = ReadText(dir / "out.txt");
    EXPECT_NE(text.find(says), std::string::npos) << noise << "\n" << text;
    EXPECT_NE(text.find("config.yaml:"), std::string::npos) << text;
    EXPECT_NE(text.find("noise"), std::string::npos) << text;
    EXPECT_FALSE(fs::exists(dir / "out" / "results.json")) << noise;
    fs::remove_all(dir);
  }
}

}  // namespace filter_error_run_test
}  // namespace vesselid
