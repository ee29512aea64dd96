// The pieces of `vesselid design` on the second-order Nomoto model: the information of a
// planned record against finite differences of an independent simulation, the nuisance
// marginalised, the criteria and standard errors on known matrices, every family's plan
// within its limits, and the box kept by the search.
#include <cmath>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/design/design_config.h"
#include "engine/design/design_criterion.h"
#include "engine/design/design_limits.h"
#include "engine/design/design_search.h"
#include "engine/design/input_commands.h"
#include "engine/design/planned_information.h"
#include "engine/design/planned_record.h"
#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace design_test {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Nomoto {
  ModelRegistry registry = DefaultRegistry();
  std::shared_ptr<const ModelHandle> model;
  std::vector<double> p;  // T1, T2, T3, K, delta_0: the cargo ship
  Nomoto() {
    std::string error;
    model = registry.MakeModel("nomoto", {{"type", "second_order"}}, &error);
    p = {45.0, 6.0, 10.0, 0.09, 0.0};
  }
};

DesignOptions StepsOptions(DesignInput::Family family) {
  DesignOptions o;
  DesignInput in;
  in.name = "delta";
  in.family = family;
  in.lower = -35 * kDeg;
  in.upper = 35 * kDeg;
  in.rate = 2.3 * kDeg;
  in.hold = 20.0;
  in.headings = {5 * kDeg, 30 * kDeg};
  o.inputs = {in};
  return o;
}

TEST(PlannedInformation, MatchesFiniteDifferencesOfTheSimulation) {
  Nomoto n;
  ASSERT_NE(n.model, nullptr);
  const DesignOptions options = StepsOptions(DesignInput::Family::kSteps);
  DesignLayout layout;
  std::string error;
  ASSERT_TRUE(MakeDesignLayout(n.model->info(), options, 200.0, &layout, &error)) << error;
  const Actuators actuators = MakeActuators(n.model->info(), options, layout);
  std::vector<double> z(layout.variables);
  for (int i = 0; i < layout.variables; ++i) z[i] = (i % 3 == 0) ? 1.0 : (i % 3 == 1 ? 0.0 : 0.7);
  const std::vector<double> x0(3, 0.0);
  PlannedRecord record;
  const Manoeuvre plan = CommandOf(options, layout, z);
  ASSERT_TRUE(RealizePlan(*n.model, n.p, x0, 200.0, 0.5, 0.1, actuators, plan.command, &record));
  InformationSetup setup;
  setup.parameters = {0, 1, 2, 3};
  setup.sigma = {0.002, std::nan("")};  // psi measured, r not
  setup.max_step = 0.1;
  Eigen::MatrixXd information;
  ASSERT_TRUE(PlannedInformation(*n.model, record, n.p, x0, setup, &information, &error)) << error;
  // Central differences of the heading from RealizePlan (the same inputs, open loop).
  const int m = static_cast<int>(record.time.size());
  Eigen::MatrixXd s(m, 4);
  for (int j = 0; j < 4; ++j) {
    const double h = 1e-5 * std::abs(n.p[j]);
    std::vector<double> up = n.p, down = n.p;
    up[j] += h;
    down[j] -= h;
    PlannedRecord a, b;
    ASSERT_TRUE(RealizePlan(*n.model, up, x0, 200.0, 0.5, 0.1, actuators,
                            CommandOf(options, layout, z).command, &a));
    ASSERT_TRUE(RealizePlan(*n.model, down, x0, 200.0, 0.5, 0.1, actuators,
                            CommandOf(options, layout, z).command, &b));
    s.col(j) = (a.outputs.col(0) - b.outputs.col(0)) / (2 * h) / 0.002;
  }
  const Eigen::MatrixXd expected = s.transpose() * s;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      EXPECT_NEAR(information(a, b), expected(a, b),
                  1e-4 * std::sqrt(expected(a, a) * expected(b, b)))
          << a << "," << b;
    }
  }
  // A free initial heading costs information (the Schur complement is smaller), never adds.
  setup.free_states = {0};
  Eigen::MatrixXd marginal;
  ASSERT_TRUE(PlannedInformation(*n.model, record, n.p, x0, setup, &marginal, &error));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> lost(information - marginal);
  EXPECT_GE(lost.eigenvalues().minCoeff(), -1e-9 * information.norm());
  EXPECT_GT((information - marginal).norm(), 0.0);
}

TEST(DesignCriterion, KnownMatrices) {
  Eigen::MatrixXd m(2, 2);
  m << 4.0, 0.0, 0.0, 1.0;
  EXPECT_NEAR(CriterionValue(m, DesignCriterion::kD, -1), -std::log(4.0), 1e-6);
  EXPECT_NEAR(CriterionValue(m, DesignCriterion::kA, -1), 1.25, 1e-6);
  EXPECT_NEAR(CriterionValue(m, DesignCriterion::kE, -1), -1.0, 1e-12);
  EXPECT_NEAR(CriterionValue(m, DesignCriterion::kParameter, 0), 0.25, 1e-6);
  const std::vector<double> se = PredictedStdErrors(m, {1.0, 1.0});
  EXPECT_NEAR(se[0], 0.5, 1e-12);
  EXPECT_NEAR(se[1], 1.0, 1e-12);
  // A direction without information: its parameters undetermined, the other finite.
  Eigen::MatrixXd singular(3, 3);
  singular << 1, 1, 0, 1, 1, 0, 0, 0, 2;
  const std::vector<double> partial = PredictedStdErrors(singular, {1.0, 1.0, 1.0});
  EXPECT_TRUE(std::isinf(partial[0]));
  EXPECT_TRUE(std::isinf(partial[1]));
  EXPECT_NEAR(partial[2], std::sqrt(0.5), 1e-12);
  // The information of a covariance is its inverse where it is regular.
  Eigen::MatrixXd c(2, 2);
  c << 2.0, 0.5, 0.5, 1.0;
  EXPECT_NEAR((InformationOfCovariance(c) - c.inverse()).norm(), 0.0, 1e-9);
}

// Every family's plan keeps amplitude, rate and duration, whatever the design variables.
TEST(DesignLimits, EveryFamilyKeepsItsLimits) {
  Nomoto n;
  for (const auto family : {DesignInput::Family::kSteps, DesignInput::Family::kMultisine,
                            DesignInput::Family::kZigzag}) {
    const DesignOptions options = StepsOptions(family);
    DesignLayout layout;
    std::string error;
    ASSERT_TRUE(MakeDesignLayout(n.model->info(), options, 300.0, &layout, &error)) << error;
    const Actuators actuators = MakeActuators(n.model->info(), options, layout);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> z(layout.variables);
      for (int i = 0; i < layout.variables; ++i)
        z[i] = std::fmod(0.37 * (i + 1) * (trial + 2), 1.0);
      PlannedRecord record;
      ASSERT_TRUE(RealizePlan(*n.model, n.p, {0, 0, 0}, 300.0, 0.5, 0.5, actuators,
                              CommandOf(options, layout, z).command, &record));
      EXPECT_TRUE(CheckLimits(options, layout, actuators, record, {}, {"psi", "r"}, 0.5).empty());
      for (int k = 0; k < record.inputs.rows(); ++k) {
        EXPECT_LE(std::abs(record.inputs(k, 0)), 35 * kDeg + 1e-12);
        if (k > 0) {
          EXPECT_LE(std::abs(record.inputs(k, 0) - record.inputs(k - 1, 0)),
                    2.3 * kDeg * 0.5 + 1e-12);
        }
      }
      EXPECT_NEAR(record.time.back(), 300.0, 1e-9);
    }
  }
  // The check does fire: a record beyond the range and the rate.
  const DesignOptions options = StepsOptions(DesignInput::Family::kSteps);
  DesignLayout layout;
  std::string error;
  ASSERT_TRUE(MakeDesignLayout(n.model->info(), options, 10.0, &layout, &error));
  const Actuators actuators = MakeActuators(n.model->info(), options, layout);
  PlannedRecord bad;
  bad.time = {0.0, 0.5, 1.0};
  bad.inputs = Eigen::MatrixXd::Zero(3, 1);
  bad.inputs(1, 0) = 40 * kDeg;
  bad.outputs = Eigen::MatrixXd::Zero(3, 2);
  const std::vector<std::string> found =
      CheckLimits(options, layout, actuators, bad, {}, {"psi", "r"}, 0.5);
  ASSERT_EQ(found.size(), 2u);  // too short, and outside [lower, upper]
}

// The search keeps the predicted heading inside a box and never does worse than its starts.
TEST(DesignSearch, KeepsTheBox) {
  Nomoto n;
  DesignContext c;
  c.model = n.model.get();
  c.members = {n.p};
  c.x0 = {0, 0, 0};
  c.setup.parameters = {0, 1, 2, 3};
  c.setup.sigma = {0.002, std::nan("")};
  c.setup.max_step = 0.5;
  c.scale = {45.0, 6.0, 10.0, 0.09};
  c.current = Eigen::MatrixXd::Identity(4, 4) * 1e-2;
  c.options = StepsOptions(DesignInput::Family::kSteps);
  c.options.starts = 6;
  c.options.max_evaluations = 200;
  c.options.refined = 2;
  c.options.threads = 1;
  std::string error;
  ASSERT_TRUE(MakeDesignLayout(n.model->info(), c.options, 300.0, &c.layout, &error));
  c.actuators = MakeActuators(n.model->info(), c.options, c.layout);
  c.sample_time = 0.5;
  c.box = {{0, {-0.3, 0.3}}};  // psi within +-0.3 rad of the start
  SearchResult result;
  ASSERT_TRUE(SearchDesign(c, &result, &error)) << error;
  EXPECT_LE(result.best.box_violation, 1e-6);
  for (int k = 0; k < result.best.record.outputs.rows(); ++k) {
    EXPECT_LE(std::abs(result.best.record.outputs(k, 0)), 0.3 + 1e-6);
  }
  EXPECT_TRUE(
      CheckLimits(c.options, c.layout, c.actuators, result.best.record, c.box, {"psi", "r"}, 0.5)
          .empty());
  // Well above the quiet start that keeps the box by doing nothing.
  const std::vector<double> quiet = QuietDesign(c.options, c.layout);
  const PlanEvaluation nothing = EvaluatePlan(
      c, [&] { return CommandOf(c.options, c.layout, quiet); }, false);
  EXPECT_LT(result.best.criterion, nothing.criterion - 1.0);
}

TEST(DesignConfig, BadKeysNameFileLineAndKey) {
  const std::string head = "model: {family: nomoto, type: second_order}\ndesign:\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"  sample_time: 0.5\n  inputs: {delta: {family: jumps, lower: -1, upper: 1}}\n",
       "design.inputs.delta.family: unknown family 'jumps'"},
      {"  sample_time: 0.5\n  inputs: {delta: {family: steps, lower: 1, upper: -1}}\n",
       "design.inputs.delta: needs lower < upper"},
      {"  sample_time: 0.5\n  inputs: {delta: {family: steps, lower: -1, upper: 1}}\n  speed: 3\n",
       "design.speed: unknown key"},
      {"  sample_time: 0.5\n  criterion: F\n  inputs: {delta: {family: fixed, value: 0}}\n",
       "design.criterion: D, A, E or {parameter: <name>}"},
      {"  sample_time: 0.5\n  box: {n: [5, 10]}\n  inputs: {delta: {family: fixed, value: 0}}\n",
       "design.box.n: [lower, upper] around the start"},
  };
  for (const auto& [body, expected] : cases) {
    DesignOptions options;
    std::string error;
    EXPECT_FALSE(LoadDesign("config.yaml", &options, &error, head + body));
    EXPECT_NE(error.find("config.yaml:"), std::string::npos) << error;
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  }
}

}  // namespace design_test
}  // namespace vesselid
