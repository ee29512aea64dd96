// A labelled corpus of identification runs for calibrating the verdict (diagnose/): the
// patrol vessel's steering simulated in closed loop (a first-order steering gear, heading
// noise, compass quantisation, a rudder bias the model lacks) and fitted with second-order
// Nomoto configs, some right and some wrong (a heading read in the wrong unit, bounds that
// exclude the truth, a time constant held at a wrong value, a sign flipped, an iteration limit,
// an unmodelled rudder bias). Each run is labelled by its known truth, not by what the engine
// says: good when the structure is right and every free parameter is determined (a standard
// error below 50 % of its value, off its bounds) and lies within max(3 SE, 5 %) of its true
// value; bad otherwise (a wrong structure is bad whatever the estimates).
// tests/system/verdict_corpus_test.cc requires the verdicts to agree; benchmark_verdicts prints
// the confusion matrix per finding kind.
#pragma once

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/finding_report.h"
#include "problems/registry.h"

namespace vesselid::testing {

struct CorpusCase {
  std::string name;
  std::string simulation;  // the experiment's simulation keys (excitation, noise, bias)
  bool degrees = false;    // the simulator logs angles in degrees
  std::string experiment;  // extra keys of the experiment (degrees:)
  std::string parameters;  // the stage's parameters map
  std::string stage;       // extra keys of the stage
  bool wrong_structure = false;
};

struct CorpusOutcome {
  std::string name;
  bool good = false;   // the label, from the truth
  std::string why;     // what made it bad
  bool ran = false;
  Verdict verdict = Verdict::kGood;
  std::vector<Finding> findings;  // every finding of the run
};

inline const std::map<std::string, double>& CorpusTruth() {
  static const std::map<std::string, double> truth = {
      {"T1", 2.0875}, {"T2", 0.3179}, {"T3", 0.1830}, {"K", -0.1724}};
  return truth;
}

// "T1: {start: ..., lower: 0.01, upper: 20}, ..." with every start `scale[i]` x the truth.
inline std::string CorpusParameters(const std::vector<double>& scale,
                                    const std::string& k_bounds = "lower: -2.0, upper: -0.001") {
  const char* names[4] = {"T1", "T2", "T3", "K"};
  const char* bounds[4] = {"lower: 0.01, upper: 20.0", "lower: 0.01, upper: 20.0",
                           "lower: 0.0, upper: 5.0", nullptr};
  std::string text = "{";
  for (int i = 0; i < 4; ++i) {
    char item[160];
    std::snprintf(item, sizeof(item), "%s%s: {start: %.6g, %s}", i > 0 ? ", " : "", names[i],
                  CorpusTruth().at(names[i]) * scale[i],
                  bounds[i] != nullptr ? bounds[i] : k_bounds.c_str());
    text += item;
  }
  return text + "}";
}

inline std::vector<CorpusCase> VerdictCorpus() {
  const std::vector<std::string> excitations = {
      "excitation: {type: sine, amplitude_deg: 20, period: 30}",
      "excitation: {type: zigzag, rudder_deg: 10, heading_deg: 10}",
      "excitation: {type: multisine, amplitude_deg: 15, periods: [12, 30, 70]}"};
  std::mt19937 random(2026);
  std::uniform_real_distribution<double> near(0.8, 1.2), far(0.5, 1.5);
  auto starts = [&](std::uniform_real_distribution<double>& d) {
    return std::vector<double>{d(random), d(random), d(random), d(random)};
  };
  std::vector<CorpusCase> cases;
  for (size_t e = 0; e < excitations.size(); ++e) {
    const std::string x = excitations[e] + ", seed: " + std::to_string(11 + e);
    const std::string tag = std::to_string(e);
    // Right structure, starts within 20 %: heading noise 0, 0.05 and 0.2 deg, two starts each.
    for (double noise : {0.0, 0.02, 0.05}) {
      for (int s = 0; s < 2; ++s) {
        char n[64];
        std::snprintf(n, sizeof(n), "noise: {heading_deg: %g}", noise);
        cases.push_back({"good_x" + tag + "_noise" + std::to_string(noise).substr(0, 4) + "_s" +
                             std::to_string(s),
                         x + ", " + n, false, "", CorpusParameters(starts(near)), ""});
      }
    }
    // A compass in half degrees; a noisy rudder (0.1 deg) the model takes as exact; a far start.
    cases.push_back({"good_x" + tag + "_quantised",
                     x + ", noise: {heading_deg: 0.02, heading_resolution_deg: 0.5}", false, "",
                     CorpusParameters(starts(near)), ""});
    cases.push_back({"good_x" + tag + "_rudder_noise", x + ", noise: {rudder_deg: 0.1}", false, "",
                     CorpusParameters(starts(near)), ""});
    cases.push_back({"good_x" + tag + "_far_start", x + ", noise: {heading_deg: 0.05}", false, "",
                     CorpusParameters(starts(far)), ""});
    cases.push_back({"good_x" + tag + "_degrees_listed", x + ", noise: {heading_deg: 0.05}", true,
                     "degrees: [psi, delta]", CorpusParameters(starts(near)), ""});
    // The heading logged in degrees and read as radians (the rudder listed): K 57 x off.
    cases.push_back({"bad_x" + tag + "_heading_unit", x + ", noise: {heading_deg: 0.05}", true,
                     "degrees: [delta]", CorpusParameters(starts(near)), ""});
    // Bounds that exclude the true gain.
    for (int s = 0; s < 2; ++s) {
      cases.push_back({"bad_x" + tag + "_bound_s" + std::to_string(s),
                       x + ", noise: {heading_deg: 0.05}", false, "",
                       CorpusParameters(s == 0 ? std::vector<double>{1.1, 0.9, 1.0, 1.3}
                                               : std::vector<double>{0.9, 1.2, 0.8, 1.2},
                                        "lower: -2.0, upper: -0.19"),
                       ""});
    }
    // T1 held at 5 x its value; T2 held at 10 x its value: a wrong structure.
    cases.push_back({"bad_x" + tag + "_T1_held", x + ", noise: {heading_deg: 0.05}", false, "",
                     "{T1: {start: 10.4, role: fixed}, T2: {start: 0.3, lower: 0.01, upper: 20}, "
                     "T3: {start: 0.2, lower: 0, upper: 5}, K: {start: -0.15, lower: -2, upper: "
                     "-0.001}}",
                     "", true});
    cases.push_back({"bad_x" + tag + "_T2_held", x + ", noise: {heading_deg: 0.05}", false, "",
                     "{T1: {start: 2.0, lower: 0.01, upper: 20}, T2: {start: 3.2, role: fixed}, "
                     "T3: {start: 0.2, role: fixed}, K: {start: -0.15, lower: -2, upper: -0.001}}",
                     "", true});
    cases.push_back({"bad_x" + tag + "_K_held", x + ", noise: {heading_deg: 0.05}", false, "",
                     "{T1: {start: 2.0, lower: 0.01, upper: 20}, T2: {start: 0.3, lower: 0.01, "
                     "upper: 20}, T3: {start: 0.2, lower: 0, upper: 5}, K: {start: -0.086, role: "
                     "fixed}}",
                     "", true});
    // The gain's sign flipped by its bounds: K in [0.001, 2].
    cases.push_back({"bad_x" + tag + "_sign", x + ", noise: {heading_deg: 0.05}", false, "",
                     CorpusParameters({1.0, 1.0, 1.0, -1.0}, "lower: 0.001, upper: 2.0"), ""});
    // Two iterations from a far start.
    cases.push_back({"bad_x" + tag + "_two_iterations", x + ", noise: {heading_deg: 0.05}", false,
                     "", CorpusParameters({1.6, 0.5, 1.5, 0.6}),
                     "    local: {max_iterations: 2}\n"});
    // A rudder indicator 3 and 6 deg off its zero that the model does not know of.
    for (double bias : {3.0, 6.0}) {
      char b[64];
      std::snprintf(b, sizeof(b), ", rudder_bias_deg: %g", bias);
      cases.push_back({"bad_x" + tag + "_bias" + std::to_string(static_cast<int>(bias)),
                       x + ", noise: {heading_deg: 0.05}" + b, false, "",
                       CorpusParameters(starts(near)), ""});
    }
  }
  // Multi-sines of other amplitudes, periods and noise: well-determined fits from near starts.
  for (int k = 0; k < 8; ++k) {
    char x[200];
    std::snprintf(x, sizeof(x),
                  "excitation: {type: multisine, amplitude_deg: %d, periods: [%d, 30, 70]}, "
                  "seed: %d, noise: {heading_deg: %g}",
                  12 + 2 * k, 9 + k, 40 + k, k % 2 == 0 ? 0.01 : 0.03);
    cases.push_back({"good_ms" + std::to_string(k), x, false, "", CorpusParameters(starts(near)),
                     ""});
  }
  return cases;
}

inline std::string CorpusConfig(const CorpusCase& c) {
  return std::string(
             "model: {family: nomoto, type: second_order}\n"
             "simulation:\n"
             "  truth: {T1: 2.0875, T2: 0.3179, T3: 0.1830, K: -0.1724}\n"
             "  steering_gear: {Tm: 1.0, kp: 0.7, rudder_limit_deg: 35}\n"
             "  sample_time: 0.05\n") +
         (c.degrees ? "  degrees: true\n" : "") +
         "  experiments:\n"
         "    - {file: run.csv, duration: 300, " +
         c.simulation +
         "}\n"
         "experiments:\n"
         "  - {name: run, file: run.csv, inputs: {delta: delta}, outputs: {psi: psi}" +
         (c.experiment.empty() ? "" : ", " + c.experiment) +
         "}\n"
         "stages:\n"
         "  - name: fit\n"
         "    parameters: " +
         c.parameters + "\n" + c.stage;
}

// Simulates and runs one case in `dir` (created), labels it by the truth.
inline CorpusOutcome RunCorpusCase(const CorpusCase& c, const std::filesystem::path& dir,
                                   std::string* error) {
  namespace fs = std::filesystem;
  CorpusOutcome outcome;
  outcome.name = c.name;
  fs::create_directories(dir);
  std::ofstream(dir / "config.yaml") << CorpusConfig(c);
  ConfigFile file;
  if (!LoadConfigFile((dir / "config.yaml").string(), dir.string(), DefaultRegistry(), &file,
                      error) ||
      !SimulateConfig(file, dir.string(), error)) {
    return outcome;
  }
  RunResult result;
  Identify(file.run, &result, error);
  if (result.stages.empty()) return outcome;
  outcome.ran = true;
  outcome.verdict = result.verdict;
  outcome.findings = AllFindings(result);
  outcome.good = !c.wrong_structure && result.stopped_stage.empty();
  if (c.wrong_structure) outcome.why = "wrong structure";
  for (const Estimate& e : result.stages.back().estimates) {
    if (e.kind != EstimateKind::kParameter || e.role == ParameterRole::kFixed) continue;
    const auto truth = CorpusTruth().find(e.name);
    if (truth == CorpusTruth().end()) continue;
    const double tolerance =
        std::max(std::isfinite(e.std_error) ? 3.0 * e.std_error : 0.0, 0.05 * std::abs(truth->second));
    const double span = 1e-6 * (e.upper - e.lower);
    const bool at_bound = e.value - e.lower <= span || e.upper - e.value <= span;
    const bool determined = std::isfinite(e.std_error) && e.std_error < 0.5 * std::abs(e.value);
    if (std::abs(e.value - truth->second) > tolerance || !determined || at_bound) {
      outcome.good = false;
      char text[128];
      std::snprintf(text, sizeof(text), "%s %.4g (truth %.4g, SE %.2g)", e.name.c_str(), e.value,
                    truth->second, e.std_error);
      outcome.why += (outcome.why.empty() ? "" : "; ") + std::string(text);
    }
  }
  return outcome;
}

}  // namespace vesselid::testing
