// The public API is engine/vesselid.h alone, and it brings neither yaml-cpp nor nlohmann/json
// into a program: their include guards stay undefined here (this source is compiled without
// the tests' precompiled headers, which hold both). Through it, a program makes a model from
// plain options, loads a config given as text with its record in memory, identifies, and gets
// results.json's text.
#include "engine/vesselid.h"

#if defined(YAML_H_62B23520_7C8E_11DE_8A39_0800200C9A66) || \
    defined(NODE_NODE_H_62B23520_7C8E_11DE_8A39_0800200C9A66)
#error "engine/vesselid.h includes yaml-cpp"
#endif
#if defined(INCLUDE_NLOHMANN_JSON_HPP_) || defined(INCLUDE_NLOHMANN_JSON_FWD_HPP_)
#error "engine/vesselid.h includes nlohmann/json"
#endif

#include <cmath>
#include <memory>
#include <string>

#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace public_api_test {

// A first-order Nomoto ship (T 8 s, K 0.12 1/s) under a rudder sine, integrated here.
std::shared_ptr<Trajectory> SineRecord() {
  auto record = std::make_shared<Trajectory>();
  record->names = {"delta", "psi"};
  record->columns.resize(2);
  const double T = 8.0, K = 0.12, dt = 0.1;
  double psi = 0.0, r = 0.0;
  for (int i = 0; i <= 3000; ++i) {
    const double t = i * dt, delta = 0.1 * std::sin(0.05 * t);
    record->t.push_back(t);
    record->columns[0].push_back(delta);
    record->columns[1].push_back(psi);
    for (int k = 0; k < 10; ++k) {  // Euler substeps: accurate enough for a start 30 % off
      const double h = dt / 10.0;
      psi += h * r;
      r += h * (K * delta - r) / T;
    }
  }
  return record;
}

TEST(PublicApi, ModelFromPlainOptions) {
  const ModelRegistry registry = DefaultRegistry();
  std::string error;
  auto model = registry.MakeModel("nomoto", {{"type", "first_order"}}, &error);
  ASSERT_NE(model, nullptr) << error;
  EXPECT_EQ(model->info().states.size(), 2u);
  EXPECT_EQ(registry.MakeModel("nomoto", {{"type", "fifth_order"}}, &error), nullptr);
  EXPECT_NE(error.find("model.type"), std::string::npos) << error;
}

TEST(PublicApi, ConfigAsTextWithARecordInMemoryToResultsJson) {
  ConfigSource source;
  source.path = "api.yaml";
  source.text = R"(
model: {family: nomoto, type: first_order}
experiments:
  - {name: sine, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: fit
    parameters:
      T: {start: 10.4, lower: 1, upper: 100}
      K: {start: 0.084, lower: 0.01, upper: 1}
)";
  source.in_memory = {"sine"};
  const ModelRegistry registry = DefaultRegistry();
  ConfigFile config;
  std::string error;
  ASSERT_TRUE(LoadConfig(source, registry, &config, &error)) << error;
  config.run.experiments[0].table = SineRecord();
  RunResult result;
  ASSERT_TRUE(Identify(config.run, &result, &error)) << error;
  const std::string json = RunResultJsonText(config.run, result);
  EXPECT_NE(json.find("\"verdict\""), std::string::npos);
  bool found = false;
  for (const FinalParameter& p : result.parameters) {
    if (p.name != "T") continue;
    found = true;
    EXPECT_NEAR(p.value, 8.0, 0.3);  // the record's Euler substeps against the model's RK4
  }
  EXPECT_TRUE(found);
}

}  // namespace public_api_test
}  // namespace vesselid
