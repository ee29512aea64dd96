// Bootstrap standard errors of a step-regression stage on the shipped craft campaign
// (configs/eriksen_2dof.yaml: a physical planing craft in current and gusty wind, which the
// 2-DOF model only approximates), regression stage only, through the command line.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "tests/support/findings.h"
#include "tests/support/simulated_records.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace step_regression_bootstrap_test {

namespace fs = std::filesystem;

class StepRegressionBootstrap : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // Own folder per process: CTest runs the cases of this suite in parallel.
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_step_regression_bootstrap_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/eriksen_2dof.yaml";
    data_ = new fs::path(testing::SimulatedRecords("eriksen_2dof"));
    ASSERT_FALSE(data_->empty()) << "vesselid simulate " << config;
    std::ifstream in(config);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    regression_ = new std::string(text.substr(0, text.find("  - name: refinement")));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete data_;
    delete regression_;
  }

  // Runs the regression stage with `keys` added to its step_regression map; the exit status
  // and (on success) results.json, report.txt and report.html.
  static int Run(const std::string& name, const std::string& keys, nlohmann::json* results,
                 std::string* report, std::string* html, std::string* stderr_text) {
    std::string text = *regression_;
    const std::string anchor = "      asymptote:";
    text.insert(text.find(anchor), keys);
    const fs::path file = *dir_ / (name + ".yaml"), out = *dir_ / name;
    std::ofstream(file) << text;
    const std::string command = std::string(VESSELID_BINARY) + " run " + file.string() +
                                " --data " + data_->string() + " --out " + out.string() +
                                " --quiet > /dev/null 2> " + (out.string() + ".err");
    const int status = std::system(command.c_str());
    auto read = [](const fs::path& path) {
      std::ifstream in(path);
      return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    *stderr_text = read(out.string() + ".err");
    if (status == 0) {
      std::ifstream in(out / "results.json");
      *results = nlohmann::json::parse(in);
      *report = read(out / "report.txt");
      *html = read(out / "report.html");
    }
    return status;
  }

  static fs::path* dir_;
  static fs::path* data_;  // the shipped config's simulated records, shared (read only)
  static std::string* regression_;
};

fs::path* StepRegressionBootstrap::dir_ = nullptr;
fs::path* StepRegressionBootstrap::data_ = nullptr;
std::string* StepRegressionBootstrap::regression_ = nullptr;

TEST_F(StepRegressionBootstrap, EveryNonZeroEstimateGetsABootstrapStandardError) {
  nlohmann::json results;
  std::string report, html, errors;
  ASSERT_EQ(Run("default", "", &results, &report, &html, &errors), 0) << errors;
  const nlohmann::json& stage = results["stages"][0];
  const nlohmann::json& b = stage["bootstrap"];
  EXPECT_EQ(b["runs"], 200);  // the default
  EXPECT_EQ(b["lambda"], "held");
  EXPECT_EQ(b["failed"], 0);
  EXPECT_GT(b["groups"].get<int>(), 20);
  double largest = 0.0;
  for (const auto& e : stage["estimates"]) largest = std::max(largest, std::abs(e["value"].get<double>()));
  int selected = 0;
  for (const auto& e : stage["estimates"]) {
    const std::string name = e["name"];
    if (name.size() > 2 && (name.substr(name.size() - 2) == ".a" || name.substr(name.size() - 2) == ".b")) {
      EXPECT_TRUE(e["std_error"].is_null()) << name << ": (a, b) are held with lambda";
      continue;
    }
    ASSERT_TRUE(b["se"].contains(name)) << name;
    if (std::abs(e["value"].get<double>()) <= 1e-9 * largest) continue;  // dropped by the lasso
    ++selected;
    const double se = e["std_error"].get<double>();
    EXPECT_TRUE(std::isfinite(se) && se > 0.0) << name;
    EXPECT_EQ(se, b["se"][name].get<double>()) << name;
    const auto interval = b["interval"][name];
    EXPECT_LE(interval[0].get<double>(), interval[1].get<double>()) << name;
  }
  EXPECT_GT(selected, 10);
  ASSERT_FALSE(b["zero_share"].empty());
  for (const auto& [name, share] : b["zero_share"].items()) {
    EXPECT_GE(share.get<double>(), 0.0) << name;
    EXPECT_LE(share.get<double>(), 1.0) << name;
  }
  // The symmetry the mirrored samples impose: sigma_U is even in r, so its r term is never
  // selected; sigma_r's r term always is.
  EXPECT_EQ(b["zero_share"]["sigma_U.r"].get<double>(), 1.0);
  EXPECT_EQ(b["zero_share"]["sigma_r.r"].get<double>(), 0.0);
  EXPECT_NE(report.find("bootstrap over"), std::string::npos);
  EXPECT_NE(report.find("lasso selection"), std::string::npos);
  EXPECT_NE(html.find("<h4>Bootstrap</h4>"), std::string::npos);
  // Doubtful estimates are named in the findings (stderr, report, results.json).
  EXPECT_FALSE(
      testing::JsonFindingsOf(results, "bootstrap", "bootstrap interval contains 0 for").empty());
  EXPECT_NE(errors.find("bootstrap interval contains 0 for"), std::string::npos);
}

TEST_F(StepRegressionBootstrap, SelectingLambdaAgainBootstrapsTheAsymptoteToo) {
  nlohmann::json results;
  std::string report, html, errors;
  ASSERT_EQ(Run("selected", "      bootstrap: {runs: 2, lambda: selected, seed: 3}\n", &results,
                &report, &html, &errors), 0) << errors;
  const nlohmann::json& b = results["stages"][0]["bootstrap"];
  EXPECT_EQ(b["lambda"], "selected");
  EXPECT_EQ(b["runs"], 2);
  EXPECT_TRUE(b["se"].contains("m_U.a"));
  EXPECT_TRUE(b["se"].contains("m_r.b"));
}

TEST_F(StepRegressionBootstrap, BadKeysAreRefusedNamingTheLine) {
  nlohmann::json results;
  std::string report, html, errors;
  EXPECT_NE(Run("blocks", "      bootstrap: {runs: 20, blocks: 5}\n", &results, &report, &html,
                &errors), 0);
  EXPECT_NE(errors.find("blocks.yaml:80: stages[0].step_regression.bootstrap.blocks: unknown key"),
            std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(*dir_ / "blocks" / "results.json"));
  EXPECT_NE(Run("one", "      bootstrap: 1\n", &results, &report, &html, &errors), 0);
  EXPECT_NE(errors.find("stages[0].step_regression.bootstrap: bootstrap: runs must be 0 (none) "
                        "or >= 2, not 1"), std::string::npos) << errors;
  EXPECT_NE(Run("lambda", "      bootstrap: {lambda: sometimes}\n", &results, &report, &html,
                &errors), 0);
  EXPECT_NE(errors.find("bootstrap.lambda: expected held or selected"), std::string::npos)
      << errors;
  ASSERT_EQ(Run("none", "      bootstrap: 0\n", &results, &report, &html, &errors), 0) << errors;
  EXPECT_FALSE(results["stages"][0].contains("bootstrap"));
  EXPECT_TRUE(results["stages"][0]["estimates"][0]["std_error"].is_null());
}

}  // namespace step_regression_bootstrap_test
}  // namespace vesselid
