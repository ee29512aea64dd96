// The shipped input-gain configs on data whose structure is not the model's: a campaign of
// the quadratic-thrust USV (problems/input_gain/quadratic_usv.h; purely quadratic thrust,
// propeller lag, cross-flow drag, Munk moment), shortened to 24 segments, with a segment that
// starts mid-manoeuvre and one GNSS fix 12 m off. Whatever the fit makes of it, the run must
// say so: no finished stage lost, a refinement worse on held-out data than its start either
// set aside (default) or named, every held-out output the refinement predicts worse named,
// and the glitched segment named as an outlier when it is a training segment.
#include <cstdlib>
#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>
#include <string>

#include "gtest/gtest.h"
#include "tests/support/findings.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kGlitchSegment = 20;

json RunMismatch(const std::string& kind, bool shortened = true) {
  std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/configs/input_gain_" + kind + ".yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  // The simulation section ends where the experiments (or their defaults) begin.
  const size_t begin = config.find("simulation:"), end = config.find("\nexperiment") + 1;
  config = config.substr(0, begin) +
           "simulation:\n  file: campaign.csv\n  vessel: quadratic_usv\n  segments: 24\n"
           "  segment_s: [20, 40]\n  duration_min: 12\n  seed: 3\n"
           "  noise: {position: 0.02, heading_deg: 0.3}\n"
           "  defects: {abrupt_start_segment: 7, glitch_segment: " +
           std::to_string(kGlitchSegment) + "}\n\n" + config.substr(end);
  // Fewer refinement iterations than shipped: the test is of what the run says, not of
  // convergence (benchmark_mismatch runs the shipped configs whole).
  const std::string refinement = "  - name: refinement\n";
  if (shortened) {
    config.insert(config.find(refinement) + refinement.size(),
                  "    local: {max_iterations: 30, num_threads: 2}\n");
  }
  const fs::path dir = fs::temp_directory_path() /
                       ("vesselid_mismatch_" + kind + (shortened ? "_short" : "_whole"));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "config.yaml") << config;
  const std::string binary = VESSELID_BINARY;
  const std::string simulate = binary + " simulate " + (dir / "config.yaml").string() + " --out " +
                               dir.string() + " > /dev/null";
  EXPECT_EQ(std::system(simulate.c_str()), 0);
  const std::string run = binary + " run " + (dir / "config.yaml").string() + " --data " +
                          dir.string() + " --out " + (dir / "out").string() +
                          " --quiet > /dev/null 2>&1";
  EXPECT_EQ(std::system(run.c_str()), 0) << run;
  std::ifstream results(dir / "out" / "results.json");
  const json j = json::parse(results, nullptr, false);
  fs::remove_all(dir);
  return j;
}

// A finding of `kind` whose message contains `text`.
bool Found(const json& results, const std::string& kind, const std::string& text) {
  return !testing::JsonFindingsOf(results, kind, text).empty();
}

void CheckRun(const std::string& kind) {
  const json results = RunMismatch(kind);
  ASSERT_FALSE(results.is_discarded());
  EXPECT_FALSE(results.contains("stopped"));
  ASSERT_EQ(results["stages"].size(), 2u);
  const json& refinement = results["stages"][1];
  ASSERT_TRUE(refinement.contains("held_out_check"));
  const json& check = refinement["held_out_check"];
  if (check["worse"].get<bool>()) {
    EXPECT_TRUE(refinement.contains("rejected"));
    EXPECT_TRUE(Found(results, "stage_set_aside", "worse on held-out data than its start"));
  } else {
    for (const json& o : check["outputs"]) {
      if (o["stage_mae"].get<double>() <= 1.01 * o["start_mae"].get<double>()) continue;
      EXPECT_TRUE(Found(results, "held_out_output_worse",
                        "predicts the held-out " + o["output"].get<std::string>() +
                            " worse than its start"))
          << o.dump();
    }
  }
  // The glitched fix makes its segment's cost stand out, when it is fitted.
  const std::string glitched = "training@" + std::to_string(kGlitchSegment);
  bool trained = false;
  for (const json& m : refinement["fit"]["metrics"]) trained |= m["experiment"] == glitched;
  if (trained) {
    EXPECT_TRUE(Found(results, "outliers", glitched)) << testing::JsonFindingsText(results);
  }
}

TEST(MismatchCampaign, StaticConfigSaysWhatItKept) { CheckRun("static"); }

TEST(MismatchCampaign, DynamicConfigSaysWhatItKept) { CheckRun("dynamic"); }

// The shipped dynamic config whole, on the purely quadratic thruster (which has no dead zone):
// its default law ends with a dead zone d_f of about 0.12 and an ahead branch that bends down
// beyond it, and an astern branch whose sign changes. Both are named: the zone as a structure
// the data do not support, the law as not monotone (a failure of the final values).
TEST(MismatchCampaign, DynamicDefaultLawsSpuriousDeadZoneIsNamed) {
  const json results = RunMismatch("dynamic", false);
  ASSERT_FALSE(results.is_discarded());
  std::map<std::string, double> value;
  for (const json& p : results["parameters"]) value[p["name"]] = p["value"].get<double>();
  EXPECT_GT(value["d_f"], 0.05);
  EXPECT_LT(value["k_f"], 0.0);
  const std::vector<json> zone =
      testing::JsonFindingsOf(results, "unsupported_structure", "the dead zone edge d_f");
  ASSERT_GE(zone.size(), 1u) << testing::JsonFindingsText(results);
  EXPECT_EQ(zone[0]["severity"], "warning");
  EXPECT_TRUE(Found(results, "not_admissible", "the thrust law is not monotone in its command"))
      << testing::JsonFindingsText(results);
  EXPECT_EQ(results["verdict"], "failed");
}

}  // namespace
}  // namespace vesselid
