// The thrust law identified on a purely quadratic thruster (the quadratic-thrust USV of
// problems/input_gain/quadratic_usv.h, not the lumped model: propeller lag, cross-flow drag,
// Munk moment) from positions in metres and heading in radians: with the craft's law
// (`thrust: ["n|n|"]`, no dead zone) no estimates compensate each other; with the seed's
// default law the linear term has nothing to fit and the run warns that b_u and k_f (or the
// other gains and k_f) compensate each other, suggesting the quadratic law; the dynamic
// default law's least squares puts a dead zone on its bound, and the run names it.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "gtest/gtest.h"
#include "tests/support/findings.h"
#include "nlohmann/json.hpp"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace thrust_law_fit_test {

namespace fs = std::filesystem;
using nlohmann::json;

// MODEL_KEYS and the thrust parameters THRUST (least squares) and THRUST_REFINED (refinement).
constexpr char kConfig[] = R"(model: {family: input_gain, type: static MODEL_KEYS}
simulation:
  file: campaign.csv
  vessel: quadratic_usv
  segments: 10
  segment_s: [20, 40]
  duration_min: 5
  seed: 5
  noise: {position: 0.02, heading_deg: 0.3}
experiments:
  - name: log
    file: campaign.csv
    inputs: {u_L: pwm_L, u_R: pwm_R}
    outputs: {n: n, e: e, psi: heading}
    interpolation: zero_order_hold
    segments: {column: segment}
stages:
  - name: least_squares
    type: least_squares
    least_squares:
      grid: n
      smoothing: {half_width: 7, order: 4}
      robust: true
      regions: {u: [ff], v: [ff, fr, rf], r: [ff, fr, rf]}
    parameters: {u.1: 0, u.u: -0.5, u.|u|u: 0, u.vr: 0, u.rr: 0, v.1: 0, v.v: -0.5, v.r: 0,
                 v.|v|v: 0, v.ur: 0, v.uv: 0, r.1: 0, r.v: 0, r.r: -0.5, r.|r|r: 0, r.uv: 0,
                 r.ur: 0, b_u: 0.5, b_v: 0.0, b_r: 1.0, THRUST}
  - name: refinement
    free_initial_states: [n, e, psi, u, v, r]
    local: {max_iterations: 25}
    parameters: {u.1: {}, u.u: {}, u.|u|u: {}, u.vr: {}, u.rr: {}, v.1: {}, v.v: {}, v.r: {},
                 v.|v|v: {}, v.ur: {}, v.uv: {}, r.1: {}, r.v: {}, r.r: {}, r.|r|r: {},
                 r.uv: {}, r.ur: {}, b_u: {}, b_v: {}, b_r: {}, THRUST_REFINED}
)";

std::string Config(const std::string& model_keys, const std::string& thrust,
                   const std::string& refined) {
  std::string text = kConfig;
  auto put = [&](const std::string& mark, const std::string& value) {
    text.replace(text.find(mark), mark.size(), value);
  };
  put("MODEL_KEYS", model_keys);
  put("THRUST_REFINED", refined);
  put("THRUST", thrust);
  return text;
}

class ThrustLawFit : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_thrust_law_fit_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "simulate.yaml") << Config("", "k_f: 0.5", "k_f: {}");
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " +
                                 (*dir_ / "simulate.yaml").string() + " --out " + dir_->string() +
                                 " > /dev/null";
    ASSERT_EQ(std::system(simulate.c_str()), 0) << simulate;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static json Run(const std::string& name, const std::string& config) {
    return testing::RunConfigOn(*dir_, name, config);
  }

  static fs::path* dir_;
};

fs::path* ThrustLawFit::dir_ = nullptr;

std::vector<std::string> Compensations(const json& results) {
  std::vector<std::string> found;
  for (const json& f : testing::JsonFindingsOf(results, "compensation")) {
    found.push_back(f["message"].get<std::string>());
  }
  return found;
}

TEST_F(ThrustLawFit, QuadraticLawHasNoCompensatingEstimates) {
  const json results =
      Run("quadratic", Config(", thrust: [\"n|n|\"], dead_zone: false", "k_r2: 0.5", "k_r2: {}"));
  ASSERT_FALSE(results.is_discarded());
  ASSERT_EQ(results["stages"].size(), 2u);
  EXPECT_TRUE(Compensations(results).empty()) << testing::JsonFindingsText(results);
}

TEST_F(ThrustLawFit, DefaultLawWarnsThatTheGainsAndKfCompensate) {
  const json results =
      Run("default", Config("", "k_f: 0.5, k_r1: 1.0, k_r2: 0.0", "k_f: {}, k_r1: {}, k_r2: {}"));
  ASSERT_FALSE(results.is_discarded());
  const std::vector<std::string> found = Compensations(results);
  bool named = false;
  for (const std::string& w : found) {
    named |= w.find("k_f") != std::string::npos && w.find("n|n|") != std::string::npos;
  }
  EXPECT_TRUE(named) << testing::JsonFindingsText(results);
}

// The dynamic variant (dead zones and a propeller lag searched inside the regressors) by its
// least-squares stage alone.
std::string DynamicLeastSquaresConfig() {
  std::string config = Config("",
                              "k_f: 0.5, k_r1: 1.0, k_r2: 0.0, "
                              "d_f: {start: 0.0, lower: 0.0, upper: 0.15}, "
                              "d_r: {start: 0.0, lower: -0.15, upper: 0.0}, "
                              "tau_T: {start: 0.3, lower: 0.02, upper: 2.0}",
                              "");
  config.replace(config.find("type: static"), 12, "type: dynamic");
  config.erase(config.find("  - name: refinement"));
  return config;
}

TEST_F(ThrustLawFit, DeadZoneAtItsBoundIsNamed) {
  std::string config = DynamicLeastSquaresConfig();
  const json results = Run("dead_zone", config);
  ASSERT_FALSE(results.is_discarded());
  bool named = false;
  for (const json& f : testing::JsonFindingsOf(results, "at_bound")) {
    const std::string text = f["message"].get<std::string>();
    named |= f["stage"] == "least_squares" && f["parameter"] == "d_f" && f["threshold"] == 0.15 &&
             text.find("is at its upper bound 0.15") != std::string::npos &&
             text.find("a dead zone at its bound stands in for a thrust law the model lacks") !=
                 std::string::npos;
  }
  EXPECT_TRUE(named) << testing::JsonFindingsText(results);
}

// least_squares.max_profile_evaluations bounds the search of the parameters inside the
// regressors (the dynamic variant's propeller lag tau_T and dead zones); the stage reports
// its evaluations as its iterations.
TEST_F(ThrustLawFit, ProfileSearchKeepsToMaxProfileEvaluations) {
  std::string config = DynamicLeastSquaresConfig();
  const json free = Run("profile_free", config);
  const std::string robust = "      robust: true\n";
  config.replace(config.find(robust), robust.size(), robust + "      max_profile_evaluations: 4\n");
  const json capped = Run("profile_capped", config);
  ASSERT_FALSE(free.is_discarded() || capped.is_discarded());
  EXPECT_GT(free["stages"][0]["iterations"].get<int>(), 4);
  EXPECT_LE(capped["stages"][0]["iterations"].get<int>(), 4);
  EXPECT_NE(free["parameters"], capped["parameters"]);
}

}  // namespace thrust_law_fit_test
}  // namespace vesselid
