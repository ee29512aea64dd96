// The input-gain thrust law as configured terms (thrust_law.h): the parameters each law has,
// the thrust it gives ahead and astern, the config keys `thrust` and `dead_zone` with their
// refusals (file, line, key), and the default law unchanged (shipped configs keep their
// numbers). input_gain_test.cc checks the regression form of the configured laws,
// model_battery_test.cc their Jacobians, RK4 order and recovery.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "gtest/gtest.h"
#include "problems/input_gain/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace thrust_law_test {

namespace fs = std::filesystem;
using input_gain::ThrustLaw;

std::vector<std::string> PropellerParameters(const ModelHandle& model) {
  const std::vector<std::string>& names = model.info().parameters;
  const auto gain = std::find(names.begin(), names.end(), "b_r");
  return std::vector<std::string>(gain + 1, names.end());
}

TEST(ThrustLaw, DefaultKeepsTheSeedParameters) {
  using V = std::vector<std::string>;
  EXPECT_EQ(PropellerParameters(*input_gain::MakeStaticHandle({})),
            (V{"k_f", "k_r1", "k_r2", "d_f", "d_r"}));
  EXPECT_EQ(PropellerParameters(*input_gain::MakeDynamicHandle({})),
            (V{"k_f", "k_r1", "k_r2", "d_f", "d_r", "tau_T"}));
  EXPECT_EQ(PropellerParameters(*input_gain::MakeStaticHandle({}, {false, true, false})),
            (V{"k_r2"}));
  EXPECT_EQ(PropellerParameters(*input_gain::MakeDynamicHandle({}, {true, false, true})),
            (V{"k_r1", "d_f", "d_r", "tau_T"}));
  EXPECT_EQ(PropellerParameters(*input_gain::MakeStaticHandle({}, {true, true, false})),
            (V{"k_f", "k_r1", "k_r2"}));
}

// Surge acceleration with every basis coefficient 0 and b_u = 1: T_L + T_R.
double SumOfThrusts(const ModelHandle& model,
                    const std::vector<std::pair<std::string, double>>& set, double pwm) {
  const ModelInfo& info = model.info();
  std::vector<double> p(info.parameters.size(), 0.0);
  p[info.ParameterIndex("b_u")] = 1.0;
  for (const auto& [name, value] : set) p[info.ParameterIndex(name)] = value;
  std::vector<double> x(info.states.size(), 0.0), xdot(info.states.size());
  const double in[2] = {pwm, pwm};
  EXPECT_TRUE(model.Derivative(x.data(), in, p.data(), xdot.data()));
  return xdot[3];
}

TEST(ThrustLaw, ThrustOfEachLaw) {
  const auto seed = input_gain::MakeStaticHandle({});
  const std::vector<std::pair<std::string, double>> coefficients = {
      {"k_f", 2.0}, {"k_r1", 0.7}, {"k_r2", 0.4}, {"d_f", 0.1}, {"d_r", -0.2}};
  // s = 0.5 - 0.1 ahead: s + k_f s^2; s = -0.7 + 0.2 astern: k_r1 s - k_r2 s^2.
  EXPECT_NEAR(SumOfThrusts(*seed, coefficients, 0.5), 2 * (0.4 + 2.0 * 0.16), 1e-12);
  EXPECT_NEAR(SumOfThrusts(*seed, coefficients, -0.7), 2 * (0.7 * -0.5 - 0.4 * 0.25), 1e-12);
  EXPECT_EQ(SumOfThrusts(*seed, coefficients, 0.05), 0.0);

  const auto quadratic = input_gain::MakeStaticHandle({}, {false, true, false});
  EXPECT_NEAR(SumOfThrusts(*quadratic, {{"k_r2", 0.4}}, 0.5), 2 * 0.25, 1e-12);
  EXPECT_NEAR(SumOfThrusts(*quadratic, {{"k_r2", 0.4}}, -0.5), 2 * -0.4 * 0.25, 1e-12);
  EXPECT_EQ(SumOfThrusts(*quadratic, {{"k_r2", 0.4}}, 0.0), 0.0);

  const auto linear = input_gain::MakeStaticHandle({}, {true, false, false});
  EXPECT_NEAR(SumOfThrusts(*linear, {{"k_r1", 0.7}}, 0.5), 2 * 0.5, 1e-12);
  EXPECT_NEAR(SumOfThrusts(*linear, {{"k_r1", 0.7}}, -0.5), 2 * 0.7 * -0.5, 1e-12);

  // Both terms without a dead zone: the quadratic ahead coefficient is k_f.
  const auto both = input_gain::MakeStaticHandle({}, {true, true, false});
  EXPECT_NEAR(SumOfThrusts(*both, {{"k_f", 2.0}}, 0.05), 2 * (0.05 + 2.0 * 0.0025), 1e-12);
}

TEST(ThrustLaw, CompensationHintsNameTheLawsRemedy) {
  const ModelInfo seed = input_gain::MakeStaticHandle({})->info();
  EXPECT_NE(seed.compensation_hints.at("k_f").find("n|n|"), std::string::npos);
  EXPECT_NE(seed.compensation_hints.at("d_f").find("dead zone"), std::string::npos);
  const ModelInfo quadratic = input_gain::MakeStaticHandle({}, {false, true, false})->info();
  EXPECT_TRUE(quadratic.compensation_hints.empty());
}

// Config text with `model_keys` in the model map and `parameters` in the stage.
class ThrustConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_thrust_law_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream data(dir_ / "log.csv");
    data << "t,n,e,heading,pwm_L,pwm_R\n";
    for (int k = 0; k < 20; ++k) data << 0.1 * k << "," << 0.1 * k << ",0,0,0.5,0.5\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  bool Load(const std::string& model_keys, const std::string& parameters, RunConfig* config,
            std::string* error) {
    std::ofstream(dir_ / "config.yaml")
        << "model: {family: input_gain, type: static" << model_keys << "}\n"
        << "experiments:\n"
        << "  - {name: log, file: log.csv, inputs: {u_L: pwm_L, u_R: pwm_R},\n"
        << "     outputs: {n: n, e: e, psi: heading}}\n"
        << "stages:\n  - name: fit\n    parameters:\n      b_u: 0.3\n"
        << parameters;
    return LoadRunConfig((dir_ / "config.yaml").string(), "", registry_, config, error);
  }

  fs::path dir_;
  ModelRegistry registry_ = DefaultRegistry();
};

TEST_F(ThrustConfig, TermsAndDeadZoneSelectTheParameters) {
  RunConfig config;
  std::string error;
  ASSERT_TRUE(Load(", thrust: [\"n|n|\"], dead_zone: false", "      k_r2: 0.5\n", &config, &error))
      << error;
  EXPECT_EQ(PropellerParameters(*config.model), std::vector<std::string>{"k_r2"});
  ASSERT_TRUE(Load(", thrust: [n|n|, n]", "      k_f: 1.0\n", &config, &error)) << error;
  EXPECT_EQ(PropellerParameters(*config.model),
            (std::vector<std::string>{"k_f", "k_r1", "k_r2", "d_f", "d_r"}));
}

TEST_F(ThrustConfig, RefusalsNameFileLineAndKey) {
  RunConfig config;
  std::string error;
  EXPECT_FALSE(Load(", thrust: [n, n^2]", "", &config, &error));
  EXPECT_NE(error.find("config.yaml:1: model.thrust[1]: unknown thrust term 'n^2' (n, n|n|)"),
            std::string::npos)
      << error;
  EXPECT_FALSE(Load(", thrust: [n, n]", "", &config, &error));
  EXPECT_NE(error.find("model.thrust[1]: term listed twice"), std::string::npos) << error;
  EXPECT_FALSE(Load(", thrust: []", "", &config, &error));
  EXPECT_NE(error.find("model.thrust: lists no term"), std::string::npos) << error;
  EXPECT_FALSE(Load(", dead_zone: maybe", "", &config, &error));
  EXPECT_NE(error.find("model.dead_zone"), std::string::npos) << error;
  EXPECT_FALSE(Load(", thrust: [\"n|n|\"]", "      k_f: 1.0\n", &config, &error));
  EXPECT_NE(error.find("k_f"), std::string::npos) << error;
  EXPECT_NE(error.find("config.yaml:"), std::string::npos) << error;
}

}  // namespace thrust_law_test
}  // namespace vesselid
