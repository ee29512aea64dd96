// The shipped input-gain configs end to end (seed 000's campaign simulated with the physical
// catamaran, 127 segments): the least-squares stage reaches the seed's one-step level, and
// the output-error refinement improves the free-run simulation of the held-out segments over
// its least-squares start, measured against the true velocities: the mean MAE ratio is below
// 0.9 (0.74 on the static config) and no velocity is more than 5 % worse. Sway gains least
// (~4 %), a margin that the BLAS kernels a machine picks and the threads' summation order can
// move either way, so it is not held to a strict improvement on its own.
#include <map>

#include "gtest/gtest.h"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace input_gain_config_test {

// (stage, prediction) -> state -> metrics
using Metrics = std::map<std::string, nlohmann::json>;

Metrics VelocityMetrics(const nlohmann::json& stage, const std::string& prediction) {
  Metrics metrics;
  for (const nlohmann::json& m : stage["velocity_validation"]) {
    if (m["prediction"] == prediction) metrics[m["state"]] = m;
  }
  return metrics;
}

void CheckRun(const std::string& name) {
  const testing::ShippedRun run = testing::SimulateAndRun(name);
  const nlohmann::json& stages = run.results["stages"];
  ASSERT_EQ(stages.size(), 2u);
  const Metrics one_step = VelocityMetrics(stages[0], "validation one-step");
  const Metrics ls = VelocityMetrics(stages[0], "validation_truth free-run");
  const Metrics oe = VelocityMetrics(stages[1], "validation_truth free-run");
  double mean_ratio = 0.0;
  for (const char* state : {"u", "v", "r"}) {
    ASSERT_TRUE(one_step.count(state) && ls.count(state) && oe.count(state)) << state;
    EXPECT_GT(one_step.at(state)["r2"].get<double>(), 0.98) << state;  // seed 000 level
    const double ratio = oe.at(state)["mae"].get<double>() / ls.at(state)["mae"].get<double>();
    EXPECT_LT(ratio, 1.05) << state;
    mean_ratio += ratio / 3.0;
  }
  EXPECT_LT(mean_ratio, 0.9);
}

TEST(InputGainConfigs, StaticLeastSquaresThenRefinement) { CheckRun("input_gain_static"); }

TEST(InputGainConfigs, DynamicLeastSquaresThenRefinement) { CheckRun("input_gain_dynamic"); }

}  // namespace input_gain_config_test
}  // namespace vesselid
