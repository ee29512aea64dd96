// `weights: noise` (per-channel noise model) end to end on the input-gain catamaran, compared
// in GNSS positions (5 Hz) and AHRS heading (50 Hz: ten times the samples of the positions):
//   * a Monte Carlo study of the output-error stage with positions at 2 cm and heading at
//     0.3 deg: the estimated sigma of every channel within 10 % of the truth, intervals
//     covering the truth (the 100-run acceptance is benchmark_noise_weights);
//   * `vesselid run` on a campaign of the physical catamaran (thrust deduction, motor lag,
//     wind: a structure the lumped model does not have): the noise model settles, is
//     reported in results.json, report.txt and report.html, the weighted residual variance is
//     ~1, and no channel's sigma is below the noise the simulator put in;
//   * a single-output stage keeps the configured weights (its result does not change).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/study_cli.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace noise_weights_test {

namespace fs = std::filesystem;
using nlohmann::json;

// A lumped static-propeller model (the least-squares estimate of a catamaran campaign); the
// Monte Carlo stage estimates five of its parameters, the truth below.
constexpr char kModel[] = R"(
  u.1: 0.08309
  u.u: -0.2078
  u.|u|u: -0.2816
  u.vr: 1.046
  u.rr: 0.02203
  v.1: 0.004088
  v.v: -0.7882
  v.r: -0.04206
  v.|v|v: -1.068
  v.ur: -0.6817
  v.uv: 0.1208
  r.1: -0.001482
  r.v: 0.5292
  r.r: -0.2147
  r.|r|r: -0.4081
  r.uv: -0.09083
  r.ur: 0.1154
  b_u: 0.2907
  b_v: -0.01729
  b_r: 0.4377
  k_f: 1.833
  k_r1: -0.1808
  k_r2: 4.867)";

const char* const kFree[] = {"u.u", "v.v", "r.r", "b_u", "b_r"};

YAML::Node Config(int runs) {
  YAML::Node config = YAML::Load(R"(
model: {family: input_gain, type: static}
simulation: {file: campaign.csv, segments: 2, duration_min: 1.2, seed: 4,
             noise: {position: 0.02, heading_deg: 0.3}}
experiments:
  - {name: training, file: campaign.csv, inputs: {u_L: pwm_L, u_R: pwm_R},
     outputs: {n: n, e: e, psi: heading}, interpolation: zero_order_hold,
     segments: {column: segment}, weights: {n: 1, e: 1, psi: 1}}
stages:
  - name: refinement
    free_initial_states: [n, e, psi, u, v, r]
    outputs: [n, e, psi]
)");
  YAML::Node parameters = YAML::Load(kModel);
  YAML::Node stage_parameters, truth;
  for (const auto& item : parameters) {
    const std::string name = item.first.as<std::string>();
    bool free = false;
    for (const char* f : kFree) free |= name == f;
    YAML::Node spec;
    spec["start"] = item.second.as<double>();
    if (!free) spec["role"] = "fixed";
    if (free) truth[name] = item.second.as<double>();
    stage_parameters[name] = spec;
  }
  config["stages"][0]["parameters"] = stage_parameters;
  config["study"] = YAML::Load("{seed: 2, monte_carlo: {stage: refinement, start: truth, "
                               "noise: {n: 0.02, e: 0.02, psi: 0.005236}}}");
  config["study"]["monte_carlo"]["runs"] = runs;
  config["study"]["monte_carlo"]["truth"] = truth;
  return config;
}

class NoiseWeights : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::StudyFolder("vesselid_noise_weights_test");
    folder_->Write("noise.yaml", Config(20));
    YAML::Node single = Config(20);
    single["stages"][0]["outputs"] = YAML::Load("[psi]");
    folder_->Write("single.yaml", single);
    YAML::Node given = single;
    given["stages"][0]["weights"] = "given";
    folder_->Write("single_given.yaml", given);
    YAML::Node unweighted = Config(20);
    unweighted["experiments"][0].remove("weights");
    folder_->Write("unweighted.yaml", unweighted);
    folder_->Simulate("noise.yaml");
  }
  static void TearDownTestSuite() { delete folder_; }
  static testing::StudyFolder* folder_;
};

testing::StudyFolder* NoiseWeights::folder_ = nullptr;

TEST_F(NoiseWeights, MonteCarloRecoversTheChannelNoiseAndCoversTheTruth) {
  std::string messages;
  ASSERT_EQ(folder_->Study("noise.yaml", "mc", &messages, "--only monte_carlo"), 0) << messages;
  const json mc = folder_->Load("mc")["monte_carlo"];
  ASSERT_TRUE(mc["noise_model"].is_object()) << mc.dump();
  EXPECT_EQ(mc["summary"]["usable_runs"], 20);
  EXPECT_EQ(mc["noise_model"]["runs"], 20);
  ASSERT_EQ(mc["noise_model"]["outputs"].size(), 3u);
  for (const json& o : mc["noise_model"]["outputs"]) {
    EXPECT_NEAR(o["mean_over_truth"].get<double>(), 1.0, 0.1) << o.dump();
  }
  for (const json& c : mc["cases"]) EXPECT_TRUE(c.contains("noise_sigma")) << c.dump();
  // Nominal 95 % intervals over 20 runs: the binomial SE of the coverage is 4.9 %, so 3 SE
  // below is 0.80 (measured 0.90-0.95). The SD of 20 estimates is itself uncertain by
  // 1/sqrt(2*19) = 16 %, so SE/SD within [0.65, 1.5] (measured 1.02-1.32): a standard error
  // half or twice the estimates' spread fails. Coverage cannot be bounded above with 20 runs
  // (all 20 covered has probability 0.36 at 95 %): the SE/SD cap catches inflated errors.
  for (const json& p : mc["summary"]["parameters"]) {
    EXPECT_GE(p["coverage"].get<double>(), 0.80) << p.dump();
    EXPECT_GT(p["std_error_over_sd"].get<double>(), 0.65) << p.dump();
    EXPECT_LT(p["std_error_over_sd"].get<double>(), 1.5) << p.dump();
  }
}

// Issue 21's acceptance (LONG): 100 runs, sigma within 10 % of the truth, coverage of the
// nominal 95 % intervals 90-99 % (>= 88 % asserted: the binomial SE of 100 runs is 2.2 %);
// the same study with `weights: given` (positions and heading weighted 1:1, one pooled
// variance) for comparison, its figures printed.
TEST_F(NoiseWeights, LongHundredRunAcceptance) {
  folder_->Write("noise100.yaml", Config(100));
  YAML::Node given = Config(100);
  given["stages"][0]["weights"] = "given";
  folder_->Write("given100.yaml", given);
  std::string messages;
  ASSERT_EQ(folder_->Study("noise100.yaml", "mc100", &messages, "--only monte_carlo"), 0)
      << messages;
  ASSERT_EQ(folder_->Study("given100.yaml", "given100", &messages, "--only monte_carlo"), 0)
      << messages;
  const json mc = folder_->Load("mc100")["monte_carlo"];
  for (const json& o : mc["noise_model"]["outputs"]) {
    // docs/configs.md "Channel weights" quotes these lines.
    std::printf("sigma %s: mean over truth %.4f\n", o.value("output", std::string()).c_str(),
                o["mean_over_truth"].get<double>());
    EXPECT_NEAR(o["mean_over_truth"].get<double>(), 1.0, 0.1) << o.dump();
  }
  for (const json& p : mc["summary"]["parameters"]) {
    EXPECT_GE(p["coverage"].get<double>(), 0.88) << p.dump();
    EXPECT_LE(p["coverage"].get<double>(), 0.99) << p.dump();
  }
  const json given_mc = folder_->Load("given100")["monte_carlo"];
  ASSERT_TRUE(given_mc.contains("noise_model"));  // stated, as null: no noise model
  EXPECT_TRUE(given_mc["noise_model"].is_null());
  for (size_t k = 0; k < mc["summary"]["parameters"].size(); ++k) {
    const json& a = given_mc["summary"]["parameters"][k];
    const json& b = mc["summary"]["parameters"][k];
    std::printf("%-6s given: SD %.4g SE/SD %.3f coverage %.2f | noise: SD %.4g SE/SD %.3f "
                "coverage %.2f\n",
                a["name"].get<std::string>().c_str(), a["sd"].get<double>(),
                a["std_error_over_sd"].get<double>(), a["coverage"].get<double>(),
                b["sd"].get<double>(), b["std_error_over_sd"].get<double>(),
                b["coverage"].get<double>());
  }
}

TEST_F(NoiseWeights, RunOnThePhysicalCatamaranReportsTheNoiseModel) {
  std::string messages;
  ASSERT_EQ(folder_->Run("noise.yaml", "run", &messages), 0) << messages;
  std::ifstream in(folder_->dir() / "run" / "results.json");
  const json stage = json::parse(in)["stages"][0];
  ASSERT_TRUE(stage.contains("noise_model")) << stage.dump();
  const json& noise = stage["noise_model"];
  EXPECT_EQ(noise["method"], "noise");
  EXPECT_TRUE(noise["converged"].get<bool>());
  EXPECT_GE(noise["iterations"].get<int>(), 1);
  EXPECT_LE(noise["iterations"].get<int>(), 5);
  // The model does not have the simulator's structure: the residuals are at least the noise
  // (0.02 m, 0.3 deg) and hold the structure's misfit besides. Measured sigma n 0.184 m,
  // e 0.069 m, psi 0.0072 rad (0.41 deg); the upper bounds (1.5x those) fail a noise model
  // that has not settled on the residuals or a fit that went wrong. (The weighted residual
  // variance is 1 by construction once sigma settles, which `converged` checks.)
  EXPECT_GT(noise["sigma"]["n"].get<double>(), 0.9 * 0.02);
  EXPECT_LT(noise["sigma"]["n"].get<double>(), 0.28);
  EXPECT_GT(noise["sigma"]["e"].get<double>(), 0.9 * 0.02);
  EXPECT_LT(noise["sigma"]["e"].get<double>(), 0.105);
  EXPECT_GT(noise["sigma"]["psi"].get<double>(), 0.9 * 0.3 * M_PI / 180.0);
  EXPECT_LT(noise["sigma"]["psi"].get<double>(), 0.011);
  EXPECT_EQ(noise["units"]["psi"], "rad");
  EXPECT_EQ(noise["samples"]["psi"].get<int>(), 10 * noise["samples"]["n"].get<int>());
  std::ifstream text(folder_->dir() / "run" / "report.txt");
  std::stringstream report;
  report << text.rdbuf();
  EXPECT_NE(report.str().find("noise model: sigma n "), std::string::npos);
  std::ifstream page(folder_->dir() / "run" / "report.html");
  std::stringstream html;
  html << page.rdbuf();
  EXPECT_NE(html.str().find("Noise model (weights 1/&sigma; per channel)"), std::string::npos);
}

// Without `weights:` on its experiments the first solve weighs each channel by the data's
// own noise level (noise_weights.h, SetDataNoiseWeights); with them, by them. The path
// differs, the noise model and the estimate it settles on do not (within 10 % and 0.2 SE).
TEST_F(NoiseWeights, FirstSolveWeighsByTheDataNoiseUnlessWeightsAreConfigured) {
  std::string messages;
  ASSERT_EQ(folder_->Run("noise.yaml", "configured", &messages), 0) << messages;
  ASSERT_EQ(folder_->Run("unweighted.yaml", "unweighted", &messages), 0) << messages;
  std::ifstream a(folder_->dir() / "configured" / "results.json");
  std::ifstream b(folder_->dir() / "unweighted" / "results.json");
  const json configured_run = json::parse(a), data_run = json::parse(b);
  const json& configured = configured_run["stages"][0];
  const json& data = data_run["stages"][0];
  ASSERT_TRUE(data.contains("noise_model")) << data.dump();
  EXPECT_TRUE(data["noise_model"]["converged"].get<bool>());
  for (const char* output : {"n", "e", "psi"}) {
    const double s1 = configured["noise_model"]["sigma"][output].get<double>();
    const double s2 = data["noise_model"]["sigma"][output].get<double>();
    EXPECT_NEAR(s2 / s1, 1.0, 0.1) << output;
  }
  int free = 0, differ = 0;
  for (size_t i = 0; i < data_run["parameters"].size(); ++i) {
    const json& x = data_run["parameters"][i];
    const json& y = configured_run["parameters"][i];
    ASSERT_EQ(x["name"], y["name"]);
    if (y["role"] != "free") continue;
    ++free;
    const double difference = std::abs(x["value"].get<double>() - y["value"].get<double>());
    differ += difference > 0.0;
    EXPECT_LT(difference, 0.2 * y["std_error"].get<double>()) << x["name"];
  }
  EXPECT_EQ(free, 5);
  EXPECT_GT(differ, 0);  // the configured weights are the first solve's
}

TEST_F(NoiseWeights, SingleOutputStageKeepsTheConfiguredWeights) {
  std::string messages;
  ASSERT_EQ(folder_->Run("single.yaml", "single", &messages), 0) << messages;
  ASSERT_EQ(folder_->Run("single_given.yaml", "single_given", &messages), 0) << messages;
  std::ifstream a(folder_->dir() / "single" / "results.json");
  std::ifstream b(folder_->dir() / "single_given" / "results.json");
  const json by_default = json::parse(a)["stages"][0], given = json::parse(b)["stages"][0];
  // Absent as in any stage with the configured weights (a noise stage has it: the test above).
  EXPECT_FALSE(by_default.contains("noise_model"));
  ASSERT_TRUE(by_default.contains("estimates"));
  EXPECT_EQ(by_default["estimates"], given["estimates"]);
}

}  // namespace noise_weights_test
}  // namespace vesselid
