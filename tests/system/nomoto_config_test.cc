// The shipped Nomoto configs end to end through the command line: simulate, run, and check
// results.json against the truth and the reported uncertainty.
#include <cmath>
#include <map>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace nomoto_config_test {

using nlohmann::json;

json RunConfig(const std::string& name) { return testing::SimulateAndRun(name).results; }

std::map<std::string, json> Estimates(const json& stage) {
  std::map<std::string, json> estimates;
  for (const json& e : stage["estimates"]) estimates[e["name"].get<std::string>()] = e;
  return estimates;
}

double RelativeError(const json& estimate, double truth) {
  return std::abs(estimate["value"].get<double>() - truth) / std::abs(truth);
}

const std::map<std::string, double> kPatrol = {
    {"T1", 2.0875}, {"T2", 0.3179}, {"T3", 0.1830}, {"K", -0.1724}};

TEST(NomotoConfigs, CargoNoiseFree) {
  json results = RunConfig("nomoto_cargo");
  auto estimates = Estimates(results["stages"][0]);
  const std::map<std::string, double> truth = {
      {"T1", 45.0}, {"T2", 6.0}, {"T3", 10.0}, {"K", 0.09}};
  for (const auto& [name, value] : truth)
    EXPECT_LT(RelativeError(estimates[name], value), 1e-4) << name;
  EXPECT_GT(results["stages"][0]["fit"]["metrics"][0]["r2"].get<double>(), 0.999999);
}

TEST(NomotoConfigs, PatrolNoiseFreeWithGlobalStart) {
  json results = RunConfig("nomoto_patrol");
  const json& stage = results["stages"][0];
  auto estimates = Estimates(stage);
  for (const auto& [name, value] : kPatrol)
    EXPECT_LT(RelativeError(estimates[name], value), 1e-4) << name;
  EXPECT_GT(stage["global_start"]["evaluations"].get<int>(), 0);
  EXPECT_GE(stage["refinements"].size(), 2u);
}

// With 0.1 deg noise the single sine leaves T2, T3 poorly determined and the run says so;
// the multi-sine determines them, and the truth lies within the reported uncertainty.
TEST(NomotoConfigs, PatrolNoiseSingleSineReportsPoorDetermination) {
  json results = RunConfig("nomoto_patrol_noise");
  auto sine = Estimates(results["stages"][0]);
  auto multisine = Estimates(results["stages"][1]);
  for (const char* name : {"T2", "T3"}) {
    const double relative_sine = sine[name]["std_error"].get<double>() / kPatrol.at(name);
    const double relative_multi = multisine[name]["std_error"].get<double>() / kPatrol.at(name);
    EXPECT_GT(relative_sine, 0.1) << name;
    EXPECT_LT(relative_multi, 0.1) << name;
    EXPECT_GT(relative_sine, 5 * relative_multi) << name;
  }
  // The T2/T3 correlation is reported and near 1 for the single sine (0.973 by the HAC covariance
  // the rudder noise makes the default here; above 0.99 by the Hessian).
  const json& correlation = results["stages"][0]["correlation"];
  const auto& names = correlation["names"];
  int t2 = -1, t3 = -1;
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "T2") t2 = static_cast<int>(i);
    if (names[i] == "T3") t3 = static_cast<int>(i);
  }
  ASSERT_GE(t2, 0);
  ASSERT_GE(t3, 0);
  // Measured |corr| 0.973 with the HAC covariance the rudder noise makes the default (the
  // Hessian's is above 0.99): 0.95 keeps the T2/T3 ridge named and fails a covariance that
  // loses it.
  EXPECT_GT(std::abs(correlation["matrix"][t2][t3].get<double>()), 0.95);
  for (const auto& [name, value] : kPatrol) {
    const double error = std::abs(multisine[name]["value"].get<double>() - value);
    EXPECT_LT(error, 3.0 * multisine[name]["std_error"].get<double>()) << name;
  }
}

}  // namespace nomoto_config_test
}  // namespace vesselid
