// configs/eriksen_2dof.yaml end to end through the command line, as a user runs it: the
// seed's step campaign and validation runs simulated with the physical craft, the regression
// stage, the output-error refinement, and what the run writes (damping and inertia samples,
// lasso paths, surfaces). The refinement must improve the free-run fit of both U and r on the
// validation runs.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace eriksen_config_test {

namespace fs = std::filesystem;

// Sample-weighted mean fit % of `output` over a stage's validation runs.
double MeanFit(const nlohmann::json& stage, const std::string& output) {
  double sum = 0.0, samples = 0.0;
  for (const auto& channel : stage["validation"]["metrics"]) {
    if (channel["output"] != output) continue;
    sum += channel["fit_percent"].get<double>() * channel["samples"].get<double>();
    samples += channel["samples"].get<double>();
  }
  return sum / samples;
}

int Lines(const fs::path& file) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(EriksenConfig, RegressionThenRefinementImprovesTheValidationFit) {
  const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/eriksen_2dof.yaml";
  const fs::path out = fs::temp_directory_path() / "vesselid_eriksen_config_test";
  fs::remove_all(out);
  const std::string binary = VESSELID_BINARY;
  ASSERT_EQ(std::system((binary + " simulate " + config + " --out " + out.string() +
                         " > /dev/null").c_str()),
            0);
  ASSERT_EQ(std::system((binary + " run " + config + " --data " + out.string() + " --out " +
                         out.string() + " --quiet > /dev/null").c_str()),
            0);
  std::ifstream in(out / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  const auto& stages = results["stages"];
  ASSERT_EQ(stages.size(), 2u);
  const auto& regression = stages[0];
  const auto& refinement = stages[1];

  // The seed's samples: steady states of 12 runs (throttle <= 0.6), mirrored, and steps.
  const auto& sr = regression["step_regression"];
  EXPECT_GT(sr["damping_samples"].get<int>(), 300);
  EXPECT_GT(sr["inertia_samples"][0].get<int>(), 100);
  EXPECT_GT(sr["inertia_samples"][1].get<int>(), 150);
  ASSERT_EQ(sr["terms"].size(), 4u);
  for (const auto& term : sr["terms"]) {
    EXPECT_GT(term["lambda"].get<double>(), 0.0) << term["name"];
    EXPECT_GT(term["r2"].get<double>(), term["name"].get<std::string>()[0] == 's' ? 0.95 : 0.1)
        << term["name"];
  }
  EXPECT_TRUE(sr["terms"][2].contains("a"));

  // Free-run validation: the refinement improves the mean fit of both outputs.
  const double u0 = MeanFit(regression, "U"), u1 = MeanFit(refinement, "U");
  const double r0 = MeanFit(regression, "r"), r1 = MeanFit(refinement, "r");
  EXPECT_GT(u0, 70.0);
  EXPECT_GT(r0, 60.0);
  EXPECT_GT(u1, u0 + 0.5) << "U fit % " << u0 << " -> " << u1;
  EXPECT_GT(r1, r0 + 0.5) << "r fit % " << r0 << " -> " << r1;

  // Exports: samples, lasso paths, the (a, b) grids and the surfaces on the configured grid.
  for (const char* name : {"regression.damping_samples.csv", "regression.inertia_samples.csv",
                           "regression.lasso_sigma_U.csv", "regression.lasso_m_r.csv",
                           "regression.asymptote_m_U.csv"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  EXPECT_EQ(Lines(out / "regression.lasso_sigma_U.csv"), 1 + 50);
  EXPECT_EQ(Lines(out / "regression.asymptote_m_U.csv"), 1 + 5 * 13);
  for (const char* name : {"regression.csv", "refinement.csv", "final.csv"}) {
    EXPECT_EQ(Lines(out / "surfaces" / name), 1 + 37 * 25) << name;
  }
  std::ifstream surface(out / "surfaces" / "final.csv");
  std::string header;
  std::getline(surface, header);
  EXPECT_EQ(header, "U,r,sigma_U,sigma_r,m_U,m_r");
  fs::remove_all(out);
}

}  // namespace eriksen_config_test
}  // namespace vesselid
