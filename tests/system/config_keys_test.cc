// Every key the README's config documents has an effect, or is refused where it cannot have
// one: each case runs a small config with and without the key and requires the results to
// differ (estimates, fits, notes, validation, final values), or requires the reader to refuse
// it naming the key. Data: three closed-loop first-order Nomoto runs (T 2 s, K -0.17) with
// heading noise, one cut into segments by a column. (`wrap` has no effect on headings that
// never pass +-pi; angle_unwrap_test.cc covers it on a turning record.)
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/config/config.h"
#include "engine/run/pipeline.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// One side of a case: what goes into the config template.
struct Variant {
  std::string a_keys;                  // added to experiment a
  std::string s_keys;                  // added to the segmented experiment s
  std::string experiments = "[a, b]";  // the stage's experiments
  std::string free = "[psi]";          // the stage's free initial states
  std::string stage;                   // stage keys
  std::string parameters;              // parameter lines (replacing a listed one by name)
  std::string top;                     // top-level keys
  std::string model;                   // added to the model map

  Variant A(std::string v) const {
    Variant c = *this;
    c.a_keys = std::move(v);
    return c;
  }
  Variant S(std::string v) const {
    Variant c = *this;
    c.s_keys = std::move(v);
    return c;
  }
  Variant E(std::string v) const {
    Variant c = *this;
    c.experiments = std::move(v);
    return c;
  }
  Variant F(std::string v) const {
    Variant c = *this;
    c.free = std::move(v);
    return c;
  }
  Variant K(std::string v) const {
    Variant c = *this;
    c.stage = std::move(v);
    return c;
  }
  Variant P(std::string v) const {
    Variant c = *this;
    c.parameters = std::move(v);
    return c;
  }
  Variant T(std::string v) const {
    Variant c = *this;
    c.top = std::move(v);
    return c;
  }
  Variant M(std::string v) const {
    Variant c = *this;
    c.model = std::move(v);
    return c;
  }
};

struct KeyCase {
  std::string name;
  Variant base, with;
  std::string refusal;  // non-empty: `with` must be refused (by the reader or before the first
                        // stage) with this in the message
};

void PrintTo(const KeyCase& c, std::ostream* os) { *os << c.name; }

constexpr char kTemplate[] = R"(model: {family: nomoto, type: first_orderMODEL_KEYS}
experiments:
  - {name: a, file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}A_KEYS}
  - {name: b, file: run1.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}, window: [0, 60]}
  - {name: c, file: run2.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r}}
  - {name: s, file: segmented.csv, inputs: {delta: delta}, outputs: {psi: psi, r: r},
     segments: {column: segment}S_KEYS}
stages:
  - name: fit
    experiments: EXPERIMENTS
    free_initial_states: FREE
STAGE_KEYS
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
      delta_0: {start: 0.0, role: fixed}
TOP_KEYS)";

const Variant V;
const Variant kLeastSquares = V.K("    type: least_squares\n    least_squares: {grid: psi}");

const KeyCase kCases[] = {
    {"interpolation", V, V.A(", interpolation: {delta: zero_order_hold}")},
    {"weights", V, V.A(", weights: {psi: 3.0}")},
    {"initial_state", V, V.A(", initial_state: {r: 0.05}")},
    {"window", V, V.A(", window: [10, 100]")},
    {"degrees", V, V.A(", degrees: [delta]")},
    {"segment_length", V, V.A(", segment_length: 30")},
    {"input_range", V, V.A(", input_range: {delta: [-0.3, 0.3]}")},
    {"segments", V, V.E("[a, s]")},
    {"stage_experiments", V, V.E("[a]")},
    {"outputs", V, V.K("    outputs: [psi]")},
    {"role_per_experiment", V, V.P("      delta_0: {start: 0.0, role: per_experiment}")},
    {"role_fixed", V, V.P("      K: {start: -0.15, role: fixed}")},
    {"free_initial_states", V, V.F("[psi, r]")},
    {"loss", V, V.K("    loss: {type: cauchy, scale: 0.001}")},
    {"integration", V, V.K("    integration: {max_step: 0.013}")},
    {"normalize_by_length", V, V.K("    normalize_by_length: false")},
    {"global", V, V.K("    global: {algorithm: GN_CRS2_LM, max_evaluations: 40, seed: 1}")},
    {"local", V, V.K("    local: {max_iterations: 2}")},
    {"continuation", V, V.K("    continuation: [20]")},
    {"continuation_on_segments", V.E("[s]"), V.E("[s]").K("    continuation: [20]")},
    {"uncertainty", V, V.K("    uncertainty: false")},
    {"validation", V, V.K("    validation: [c]")},
    {"initial_state_prior", V.E("[s]").K("    initial_state_prior: off"), V.E("[s]")},
    {"outliers", V.E("[a, b, c, s]"),
     V.E("[a, b, c, s]").K("    outliers: {action: drop, threshold: 0.01}")},
    {"type_least_squares", V, kLeastSquares},
    {"final_validation", V, V.T("final_validation: {experiments: [c]}")},
    {"fusion",
     V.P("      T: {start: 3.0, lower: 0.1, upper: 20, role: shared}")
         .T("  - name: again\n    experiments: [c]\n    parameters:\n"
            "      T: {role: shared}\n"),
     V.P("      T: {start: 3.0, lower: 0.1, upper: 20, role: shared}")
         .T("  - name: again\n    experiments: [c]\n    parameters:\n"
            "      T: {role: shared}\nfusion: mean\n")},
    // Refused combinations.
    {"initial_state_with_segments", V, V.E("[a, s]").S(", initial_state: {r: 0}"),
     "initial_state: cannot be combined with 'segments'"},
    {"continuation_in_least_squares", V,
     kLeastSquares.K(kLeastSquares.stage + "\n    continuation: [20]"),
     "stages[0].continuation: not used by a least-squares stage"},
    {"outliers_in_least_squares", V,
     kLeastSquares.K(kLeastSquares.stage + "\n    outliers: {action: drop}"),
     "stages[0].outliers: not used by a least-squares stage"},
    {"wrap_of_a_rate", V, V.A(", wrap: [r]"), "output 'r' is not an angle"},
    {"model_length_without_n1_form", V, V.M(", length: 320"),
     "model.length: only the n1-form models (first_order_n1, norrbin_n1) take a ship length"},
    {"unknown_final_choice", V, V.T("final: newest\n"), "final: unknown choice 'newest'"},
    {"separator_the_file_does_not_use", V, V.A(", separator: \";\""),
     "the header is separated by ',', not ';'"},
    {"limits", V, V.T("limits: {integration_steps: 100}\n"), "(limits.integration_steps)"},
    {"limits_of_a_study", V,
     V.T("limits: {study_cases: 5}\nstudy: {monte_carlo: {runs: 6, noise: {psi: 0.01}}}\n"),
     "study.monte_carlo.runs: 6 is more than the limit of 5 (limits.study_cases)"},
};

class ConfigKeys : public ::testing::TestWithParam<KeyCase> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_config_keys_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    auto model = nomoto::MakeFirstOrderHandle();
    for (int i = 0; i < 4; ++i) {
      nomoto::ClosedLoopOptions loop;
      loop.duration = 120.0;
      loop.sample_time = 0.05;
      loop.controller_gain = 0.7;
      loop.excitation.amplitude = 0.3;
      loop.excitation.periods = {15.0 + 5 * i};
      loop.heading_noise = 0.003;
      loop.seed = 30 + i;
      Trajectory data;
      std::string error;
      ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, &data, &error));
      std::string name = "run" + std::to_string(i) + ".csv";
      if (i == 3) {  // three segments told apart by a column
        name = "segmented.csv";
        data.names.push_back("segment");
        data.columns.emplace_back();
        for (double t : data.t) data.columns.back().push_back(t < 40 ? 1 : t < 80 ? 2 : 3);
      }
      ASSERT_TRUE(WriteTrajectoryCsv((*dir_ / name).string(), data, &error));
    }
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static std::string Text(const Variant& v) {
    std::string text = kTemplate;
    auto put = [&](const std::string& mark, const std::string& value) {
      text.replace(text.find(mark), mark.size(), value);
    };
    put("A_KEYS", v.a_keys);
    put("S_KEYS", v.s_keys);
    put("EXPERIMENTS", v.experiments);
    put("FREE", v.free);
    put("STAGE_KEYS\n", v.stage.empty() ? "" : v.stage + "\n");
    put("TOP_KEYS", v.top);
    put("MODEL_KEYS", v.model);
    if (!v.parameters.empty()) {  // replaces the listed line of the same parameter
      const std::string head = v.parameters.substr(0, v.parameters.find(':') + 1);
      const size_t at = text.find(head);
      text.replace(at, text.find('\n', at) - at, v.parameters);
    }
    return text;
  }

  // Everything a key could change, as text.
  static std::string Signature(const RunResult& r) {
    std::string s;
    char line[160];
    for (const StageResult& stage : r.stages) {
      for (const Estimate& e : stage.estimates) {
        std::snprintf(line, sizeof(line), "%s=%.12g/%.6g;", e.name.c_str(), e.value, e.std_error);
        s += line;
      }
      s += std::to_string(stage.summary.fits.size()) + " fits, " +
           std::to_string(stage.summary.refinements.size()) + " refinements, " +
           std::to_string(stage.validation.size()) + " validation;";
      for (const std::string& note : stage.summary.notes) s += note + ";";
    }
    for (const FinalParameter& f : r.parameters) {
      std::snprintf(line, sizeof(line), "%s=%.12g;", f.name.c_str(), f.value);
      s += line;
    }
    return s + std::to_string(r.final_validation.size());
  }

  static bool Load(const std::string& text, RunConfig* config, std::string* error) {
    std::ofstream(*dir_ / "config.yaml") << text;
    static const ModelRegistry registry = DefaultRegistry();
    return LoadRunConfig((*dir_ / "config.yaml").string(), "", registry, config, error);
  }

  static std::string Run(const std::string& text) {
    RunConfig config;
    RunResult result;
    std::string error;
    EXPECT_TRUE(Load(text, &config, &error)) << error << "\n" << text;
    EXPECT_TRUE(RunIdentification(config, &result, &error)) << error << "\n" << text;
    return Signature(result);
  }

  static fs::path* dir_;
};

fs::path* ConfigKeys::dir_ = nullptr;

TEST_P(ConfigKeys, HasAnEffectOrIsRefused) {
  const KeyCase& c = GetParam();
  if (!c.refusal.empty()) {
    // By the reader, or by the run before its first stage (what needs the data).
    RunConfig config;
    RunResult result;
    std::string error;
    EXPECT_FALSE(Load(Text(c.with), &config, &error) && RunIdentification(config, &result, &error))
        << Text(c.with);
    EXPECT_TRUE(result.stages.empty());
    EXPECT_NE(error.find(c.refusal), std::string::npos) << error;
    return;
  }
  EXPECT_NE(Run(Text(c.base)), Run(Text(c.with))) << Text(c.with);
}

std::string CaseName(const ::testing::TestParamInfo<KeyCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Readme, ConfigKeys, ::testing::ValuesIn(kCases), CaseName);

}  // namespace
}  // namespace vesselid
