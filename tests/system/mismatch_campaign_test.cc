// The shipped input-gain configs on data whose structure is not the model's: a campaign of
// the quadratic-thrust USV (problems/input_gain/quadratic_usv.h; purely quadratic thrust,
// propeller lag, cross-flow drag, Munk moment), shortened to 24 segments, with a segment that
// starts mid-manoeuvre and one GNSS fix 12 m off. The run must reach the held-out accuracy
// measured (with a margin the tests state), improve every held-out output on its start, and
// say what the model lacks: a verdict "failed" with the finding that names it.
#include <cmath>
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
namespace mismatch_campaign_test {

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

// What a run of the shortened campaign must reach and say: the refinement's held-out MAE per
// output below `max_mae` (e, n [m], psi [rad]; measured values times 1.5, see the tests),
// every held-out output better than the refinement's start, the verdict `verdict` with a
// finding of `failure_kind` naming `failure_text` (the model lacks the simulator's structure).
struct Expected {
  std::map<std::string, double> max_mae;
  std::string failure_kind, failure_text;
  std::string verdict = "failed";
};

void CheckRun(const std::string& kind, const Expected& expected) {
  const json results = RunMismatch(kind);
  ASSERT_FALSE(results.is_discarded());
  EXPECT_FALSE(results.contains("stopped"));
  ASSERT_EQ(results["stages"].size(), 2u);
  const json& refinement = results["stages"][1];
  ASSERT_TRUE(refinement.contains("held_out_check"));
  const json& check = refinement["held_out_check"];
  EXPECT_FALSE(check["worse"].get<bool>()) << check.dump();
  EXPECT_FALSE(refinement.contains("rejected"));
  ASSERT_EQ(check["outputs"].size(), expected.max_mae.size()) << check.dump();
  for (const json& o : check["outputs"]) {
    const std::string output = o["output"];
    ASSERT_EQ(expected.max_mae.count(output), 1u) << output;
    EXPECT_LT(o["stage_mae"].get<double>(), expected.max_mae.at(output)) << o.dump();
    EXPECT_LT(o["stage_mae"].get<double>(), o["start_mae"].get<double>()) << o.dump();
  }
  EXPECT_EQ(results["verdict"], expected.verdict);
  EXPECT_TRUE(Found(results, expected.failure_kind, expected.failure_text))
      << testing::JsonFindingsText(results);
  // The glitched fix (12 m off) falls in a held-out segment of this campaign: its north fit is
  // the worst of the final validation's.
  const std::string glitched = "validation_truth@" + std::to_string(kGlitchSegment);
  double glitched_fit = NAN, others_worst = INFINITY;
  for (const json& m : results["final_validation"]["metrics"]) {
    if (m["output"] != "n") continue;
    const double fit = m["fit_percent"].get<double>();
    if (m["experiment"] == glitched) {
      glitched_fit = fit;
    } else {
      others_worst = std::min(others_worst, fit);
    }
  }
  ASSERT_TRUE(std::isfinite(glitched_fit)) << glitched << " not in the final validation";
  if (kind == "static") {
    EXPECT_LT(glitched_fit, others_worst);
  }
}

// Measured held-out MAE from each segment's measured start (velocities on a burn-in of a tenth
// of the segment) 0.127 m (e), 0.124 m (n), 0.0232 rad (psi), better than at its start (refitted
// on the whole segments, before: 0.062, 0.050, 0.0134); the final values fit the held-out segments at 71-99.8 %, but their sway
// damping -1.54 v + 4.15 |v|v feeds the motion within the speeds the records reach.
TEST(MismatchCampaign, StaticConfigSaysWhatItKept) {
  CheckRun("static", {{{"e", 0.19}, {"n", 0.19}, {"psi", 0.035}},
                      "not_admissible",
                      "v.|v|v"});
}

// 30 refinement iterations (not converged): the propeller lag tau_T ends on its 20 ms bound
// (the simulator's thruster has none) and d_f on its 0.15 bound, both named; the run is
// doubtful, not failed. (With tau_T unbounded it went on toward 0 and the final free run of
// the velocity validation missed v, R2 -100.)
TEST(MismatchCampaign, DynamicConfigSaysWhatItKept) {
  CheckRun("dynamic", {{{"e", 3.05}, {"n", 2.9}, {"psi", 2.35}},
                       "at_bound",
                       "tau_T = 0.02 is at its lower bound",
                       "doubtful"});
}

// The shipped dynamic config whole, on the purely quadratic thruster (which has no dead zone):
// its default law ends with dead zones of about 0.15 ahead and astern (both near their
// bounds), and an astern branch that bends the wrong way beyond its edge; the damping that
// compensates feeds the motion. The zone is named as a structure the data do not support,
// the damping as not admissible (a failure of the final values). With the refinement's
// unknowns held once on their bounds the cost is 3.9e-3 (0.65 when the projected steps
// stalled with d_r on its bound; the spurious zone was then d_f, with a non-monotone law).
TEST(MismatchCampaign, DynamicDefaultLawsSpuriousDeadZoneIsNamed) {
  const json results = RunMismatch("dynamic", false);
  ASSERT_FALSE(results.is_discarded());
  std::map<std::string, double> value;
  for (const json& p : results["parameters"]) value[p["name"]] = p["value"].get<double>();
  EXPECT_GT(value["d_f"], 0.05);
  EXPECT_LT(value["d_r"], -0.05);
  const std::vector<json> zone =
      testing::JsonFindingsOf(results, "unsupported_structure", "the dead zone edge d_");
  ASSERT_GE(zone.size(), 1u) << testing::JsonFindingsText(results);
  EXPECT_EQ(zone[0]["severity"], "warning");
  EXPECT_TRUE(Found(results, "not_admissible", "damping")) << testing::JsonFindingsText(results);
  EXPECT_EQ(results["verdict"], "failed");
}

}  // namespace mismatch_campaign_test
}  // namespace vesselid
