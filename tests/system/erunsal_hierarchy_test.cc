// Seed 002's hierarchy end to end through the command line: configs/erunsal_hierarchy.yaml
// simulated (the reference tugboat's campaign) and identified from starts 30 % off. Every
// estimated parameter lies within three reported standard errors of the reference value,
// those errors capped (at 10 % of the reference where the campaign determines it),
// every stage's estimates are admissible, and the final parameters reproduce the held-out
// random-motion runs (R^2 >= 0.99 for x, y, psi).
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/erunsal6dof/erunsal_model.h"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace erunsal_hierarchy_test {

using nlohmann::json;

void RecoversEveryEstimatedParameterWithinThreeStandardErrors(const json& results) {
  const std::vector<std::string> names = erunsal6dof::ParameterNames();
  const std::vector<double> reference = erunsal6dof::ReferenceParameters();
  int estimated = 0;
  for (const json& p : results["parameters"]) {
    const std::string name = p["name"];
    const double truth = reference[std::find(names.begin(), names.end(), name) - names.begin()];
    if (p["role"] == "fixed") {
      EXPECT_DOUBLE_EQ(p["value"].get<double>(), truth) << name;
      continue;
    }
    ++estimated;
    ASSERT_FALSE(p["std_error"].is_null()) << name << " is reported undetermined";
    const double se = p["std_error"];
    EXPECT_LT(std::abs(p["value"].get<double>() - truth), 3 * se)
        << name << " = " << p["value"] << " +- " << se << ", reference " << truth;
    EXPECT_GT(se, 0.0) << name;
    // Nor an inflated error: SE at most 10 % of the reference (measured at most 4.6 %, Mq),
    // except where the campaign determines a parameter poorly: the heave decays (7 cm under
    // 2 cm noise; Zw 38 %, Zww 83 % measured), Mqq (25 %) and Yr, whose reference is -0.0001
    // (SE 0.0027 measured).
    const std::map<std::string, double> loose = {{"Zw", 1.0}, {"Zww", 1.5}, {"Mqq", 0.5}};
    const double cap = name == "Yr"           ? 0.01
                       : loose.count(name) > 0 ? loose.at(name) * std::abs(truth)
                                               : 0.1 * std::abs(truth);
    EXPECT_LT(se, cap) << name << " = " << p["value"] << " +- " << se << ", reference " << truth;
  }
  EXPECT_EQ(estimated, 24);  // 30 less Ixz, Nrdot, Zwdot, Kpdot, Mqdot, C_DA
  EXPECT_EQ(results["fusion"], "information");
}

void SharedParametersCarryEveryStageThatEstimatedThem(const json& results,
                                                     const std::string& report) {
  std::map<std::string, json> final;
  for (const json& p : results["parameters"]) final[p["name"]] = p;
  EXPECT_EQ(final["Nr"]["stages"], json({"yaw", "spiral", "zigzag"}));
  EXPECT_EQ(final["Nr"]["rule"], "information");
  EXPECT_EQ(final["Kp"]["stages"], json({"roll"}));
  EXPECT_EQ(final["Kp"]["rule"], "stage");
  EXPECT_EQ(final["L_TS"]["stages"], json({"thrust"}));
  // The table names value, standard error and the stages behind each parameter.
  EXPECT_NE(report.find("final parameters"), std::string::npos);
  EXPECT_NE(report.find("yaw, spiral, zigzag (information)"), std::string::npos);
}

void EveryStageIsAdmissibleAndValidatedOnItsHeldOutTest(const json& results) {
  const std::vector<std::string> order = {"thrust", "roll",   "pitch", "heave",
                                          "yaw",    "spiral", "zigzag"};
  ASSERT_EQ(results["stages"].size(), order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    const json& stage = results["stages"][i];
    EXPECT_EQ(stage["name"], order[i]);
    ASSERT_TRUE(stage["admissibility"].is_array()) << order[i];  // present, and empty
    EXPECT_TRUE(stage["admissibility"].empty()) << order[i];
    ASSERT_FALSE(stage["validation"]["metrics"].empty()) << order[i];
    for (const json& m : stage["validation"]["metrics"]) {
      // Short decays are measured with noise of a few percent of their amplitude (heave: 7 cm
      // with 2 cm noise), so their R^2 is noise-bound.
      const double bound = order[i] == "heave" ? 0.3 : 0.9;
      EXPECT_GT(m["r2"].get<double>(), bound) << order[i] << " " << m["experiment"] << " "
                                              << m["output"];
    }
  }
  ASSERT_TRUE(results["admissibility"].is_array());
  EXPECT_TRUE(results["admissibility"].empty());
}

void FinalParametersReproduceTheRandomMotionRuns(const json& results) {
  const json& metrics = results["final_validation"]["metrics"];
  ASSERT_EQ(metrics.size(), 6u);  // random1, random2 x (x, y, psi)
  for (const json& m : metrics) {
    EXPECT_GE(m["r2"].get<double>(), 0.99) << m["experiment"] << " " << m["output"];
  }
}

TEST(ErunsalHierarchy, ShippedConfigEndToEnd) {
  // The run takes half a minute: made once, checked in sections (CTest runs each test in its
  // own process).
  const testing::ShippedRun run = testing::SimulateAndRun("erunsal_hierarchy");
  {
    SCOPED_TRACE("parameters");
    RecoversEveryEstimatedParameterWithinThreeStandardErrors(run.results);
  }
  {
    SCOPED_TRACE("fusion");
    SharedParametersCarryEveryStageThatEstimatedThem(run.results, run.report);
  }
  {
    SCOPED_TRACE("stages");
    EveryStageIsAdmissibleAndValidatedOnItsHeldOutTest(run.results);
  }
  {
    SCOPED_TRACE("final validation");
    FinalParametersReproduceTheRandomMotionRuns(run.results);
  }
}

}  // namespace erunsal_hierarchy_test
}  // namespace vesselid
