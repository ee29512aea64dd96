// Config templates (engine/config/experiment_templates.h, experiment_sets.h, yaml_merge.h): a
// config written with experiment_defaults, anchors and merge keys, a file pattern and named
// sets loads to the same RunConfig as its long form, and errors in templated parts name the
// line where the offending text was written.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/config/config.h"
#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace config_templates_test {

namespace fs = std::filesystem;

// Everything the reader puts into a RunConfig from these configs, as text.
std::string Describe(const RunConfig& config) {
  std::string s;
  char number[64];
  auto add = [&](double v) {
    std::snprintf(number, sizeof(number), "%.17g ", v);
    s += number;
  };
  for (const ExperimentSpec& e : config.experiments) {
    s += "experiment " + e.name + " " + fs::path(e.file).lexically_normal().string() + "\n ";
    for (const auto& [k, v] : e.inputs) s += "in " + k + "=" + v + " ";
    for (const auto& [k, v] : e.outputs) s += "out " + k + "=" + v + " ";
    for (const auto& [k, v] : e.interpolation)
      s += "interp " + k + "=" + InterpolationToString(v) + " ";
    s += std::string("default ") + InterpolationToString(e.default_interpolation) + " ";
    for (const auto& [k, v] : e.output_weights) s += "w " + k + "=", add(v);
    for (const auto& [k, v] : e.initial_state) s += "x0 " + k + "=", add(v);
    for (const std::string& d : e.degree_columns) s += "deg " + d + " ";
    for (const std::string& w : e.wrapped_outputs) s += "wrap " + w + " ";
    s += "window ", add(e.t_begin), add(e.t_end);
    s += "segment_length ", add(e.segment_length);
    s += "segments " + e.segments.column + " " + std::to_string(static_cast<int>(e.segments.take)) +
         " " + std::to_string(e.segments.seed) + " ";
    add(e.segments.validation_share);
    for (const auto& [k, v] : e.input_range) s += "range " + k + " ", add(v.first), add(v.second);
    s += std::string("sep ") + e.csv.separator + "\n";
  }
  auto list = [&](const char* what, const std::vector<std::string>& names) {
    s += std::string(" ") + what;
    for (const std::string& n : names) s += " " + n;
    s += "\n";
  };
  for (const StageConfig& stage : config.stages) {
    s += "stage " + stage.options.name + " " + StageKindToString(stage.kind) + "\n";
    list("experiments", stage.experiments);
    list("validation", stage.validation);
    list("outputs", stage.experiment.outputs);
    list("free", stage.problem.free_initial_states);
    s += " loss " + stage.problem.loss + " ", add(stage.problem.loss_scale);
    s += "max_step ", add(stage.experiment.max_step);
    s += std::string("normalize ") + (stage.experiment.normalize_by_length ? "1" : "0") + "\n";
    for (const ParameterSpec& p : stage.parameters) {
      s += " parameter " + p.name + " " + ParameterRoleToString(p.role) +
           (p.start_from_previous ? " previous " : " ");
      add(p.start), add(p.lower), add(p.upper), add(p.scale);
      s += "\n";
    }
  }
  list("final", config.final_validation.experiments);
  list("final free", config.final_validation.free_initial_states);
  list("final outputs", config.final_validation.experiment.outputs);
  return s;
}

constexpr char kLongForm[] = R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: zz_1, file: data/zz_1.csv, inputs: {delta: rudder}, outputs: {psi: heading, r: rate},
     degrees: [rudder, heading], weights: {psi: 2.0, r: 1.0}, interpolation: zero_order_hold,
     window: [0, 100]}
  - {name: zz_2, file: data/zz_2.csv, inputs: {delta: rudder}, outputs: {psi: heading, r: rate},
     degrees: [rudder, heading], weights: {psi: 2.0, r: 1.0}, interpolation: zero_order_hold,
     window: [0, 100]}
  - {name: zz_3, file: data/zz_3.csv, inputs: {delta: rudder}, outputs: {psi: heading, r: rate},
     degrees: [rudder, heading], weights: {psi: 2.0, r: 0.5}, interpolation: zero_order_hold,
     window: [0, 100]}
  - {name: turn, file: data/turn.csv, inputs: {delta: rudder}, outputs: {psi: heading, r: rate},
     degrees: [heading], weights: {psi: 2.0, r: 1.0}, interpolation: zero_order_hold}
stages:
  - name: first
    experiments: [zz_1, zz_2]
    validation: [zz_3, turn]
    free_initial_states: [psi, r]
    loss: {type: cauchy, scale: 0.02}
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 50}
      K: {start: 0.1, lower: 0.001, upper: 1}
  - name: second
    experiments: [zz_1, zz_2]
    validation: [zz_3, turn]
    free_initial_states: [psi, r]
    loss: {type: huber, scale: 0.01}
    parameters:
      delta_0: {start: 0.0, role: per_experiment}
      T: {start: 3.0, lower: 0.1, upper: 50}
      K: {start: 0.1, lower: 0.001, upper: 1}
final_validation: {experiments: [zz_3, turn], free_initial_states: [psi, r]}
)";

constexpr char kShortForm[] = R"(model: {family: nomoto, type: first_order}
experiment_defaults:
  inputs: {delta: rudder}
  outputs: {psi: heading, r: rate}
  degrees: [rudder, heading]
  weights: {psi: 2.0, r: 1.0}
  interpolation: zero_order_hold
  window: [0, 100]
experiments:
  - {files: "data/zz_[12].csv"}
  - {name: zz_3, file: data/zz_3.csv, weights: {r: 0.5}}
  - {name: turn, file: data/turn.csv, degrees: [heading], window: ~}
sets:
  training: [zz_1, zz_2]
  held_out: [zz_3, turn]
stages:
  - &first
    name: first
    experiments: training
    validation: held_out
    free_initial_states: [psi, r]
    loss: {type: cauchy, scale: 0.02}
    parameters: &bounds
      T: {start: 3.0, lower: 0.1, upper: 50}
      K: {start: 0.1, lower: 0.001, upper: 1}
  - <<: [{loss: {type: huber, scale: 0.01}}, *first]
    name: second
    parameters: {delta_0: {start: 0.0, role: per_experiment}, <<: *bounds}
final_validation: {experiments: held_out, free_initial_states: [psi, r]}
)";

class ConfigTemplates : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vesselid_config_templates_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "data");
    // Loading only resolves the files; zz_10.csv is not matched by zz_[12].
    for (const char* name : {"zz_2.csv", "zz_1.csv", "zz_3.csv", "zz_10.csv", "turn.csv"}) {
      std::ofstream(dir_ / "data" / name) << "t,rudder,heading,rate\n0,0,0,0\n";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  bool Load(const std::string& text, RunConfig* config, std::string* error) {
    std::ofstream(dir_ / "config.yaml") << text;
    static const ModelRegistry registry = DefaultRegistry();
    return LoadRunConfig((dir_ / "config.yaml").string(), "", registry, config, error);
  }

  // The error of a config that must be refused.
  std::string Refusal(const std::string& text) {
    RunConfig config;
    std::string error;
    EXPECT_FALSE(Load(text, &config, &error)) << text;
    return error;
  }

  fs::path dir_;
};

TEST_F(ConfigTemplates, ShortFormLoadsToTheLongForm) {
  RunConfig long_form, short_form;
  std::string error;
  ASSERT_TRUE(Load(kLongForm, &long_form, &error)) << error;
  ASSERT_TRUE(Load(kShortForm, &short_form, &error)) << error;
  EXPECT_EQ(Describe(short_form), Describe(long_form));
  ASSERT_EQ(short_form.experiments.size(), 4u);
  EXPECT_EQ(short_form.experiments[0].name, "zz_1");              // sorted file names
  EXPECT_EQ(short_form.stages[1].parameters[0].name, "delta_0");  // merged keys at the << line
  EXPECT_EQ(short_form.experiment_sets.at("held_out"), (std::vector<std::string>{"zz_3", "turn"}));
}

TEST_F(ConfigTemplates, FilePatternFollowsTheDataFolder) {
  // The same pattern against --data: the config elsewhere, the files where --data says.
  fs::create_directories(dir_ / "elsewhere");
  std::ofstream(dir_ / "elsewhere" / "config.yaml")
      << "model: {family: nomoto, type: first_order}\n"
         "experiments:\n"
         "  - {files: \"data/zz_*.csv\", name: \"run_{stem}\", inputs: {delta: rudder},\n"
         "     outputs: {psi: heading}}\n"
         "stages:\n"
         "  - {name: fit, parameters: {T: 3.0}}\n";
  RunConfig config;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((dir_ / "elsewhere" / "config.yaml").string(), dir_.string(),
                            DefaultRegistry(), &config, &error))
      << error;
  std::vector<std::string> names;
  for (const ExperimentSpec& e : config.experiments) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"run_zz_1", "run_zz_10", "run_zz_2", "run_zz_3"}));
  EXPECT_EQ(fs::path(config.experiments[1].file), dir_ / "data" / "zz_10.csv");
}

TEST_F(ConfigTemplates, ErrorsNameTheLineWhereTheTextIs) {
  const std::string file = (dir_ / "config.yaml").string();
  auto replace = [](std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  // A default's bad value: the line of the default, with the experiment it reached.
  EXPECT_EQ(Refusal(replace(kShortForm, "weights: {psi: 2.0, r: 1.0}", "weights: {psi: -2.0}")),
            file + ":6: experiments[0](zz_1).weights.psi: weight must be >= 0");
  // A merged key where it is not allowed: the anchor's line.
  EXPECT_EQ(Refusal(replace(kShortForm, "final_validation: {experiments: held_out,",
                            "final_validation: {<<: *first, experiments: held_out,")),
            file +
                ":18: final_validation.name: unknown key (allowed: experiments, outputs, "
                "model, free_initial_states, per_experiment, held_out, initial_state_prior, reference)");
  // Two experiments of one name, one from a pattern: the pattern's line.
  EXPECT_EQ(Refusal(replace(kShortForm, "name: zz_3,", "name: zz_1,")),
            file + ":11: experiments[1].name: duplicate experiment name 'zz_1'");
  EXPECT_EQ(Refusal(replace(kShortForm, "{files: \"data/zz_[12].csv\"}",
                            "{name: zz_3, file: data/zz_3.csv}\n  - {files: \"data/zz_[3].csv\"}")),
            file + ":11: experiments[1](zz_3).name: duplicate experiment name 'zz_3'");
  // A map merging itself.
  EXPECT_EQ(
      Refusal(replace(kShortForm, "parameters: &bounds", "parameters: &bounds\n      <<: *bounds")),
      file + ":24: stages[0].parameters.<<: merges a map that contains this one");
  // Two merge keys in one map.
  EXPECT_NE(Refusal(replace(kShortForm, "    name: second", "    <<: *first\n    name: second"))
                .find(file + ":27: stages[1].<<: given twice (lines 26 and 27); a YAML map holds "
                             "each key once (merge several maps with <<: [*a, *b])"),
            std::string::npos);
}

}  // namespace config_templates_test
}  // namespace vesselid
