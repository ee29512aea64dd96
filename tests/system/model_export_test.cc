// The exported FMU and C code of every shipped config's model reproduce the engine's own
// simulation of the config's first simulated record (ModelHandle::SimulateOutputs, the path
// every fit takes) to 1e-10 relative:
// * the FMU loaded by a test master (dlopen, the fmi2* functions) and driven as a
//   co-simulation would (inputs and their slopes set at each sample, one fmi2DoStep per sample
//   interval); modelDescription.xml checked for the FMI 2.0 rules that matter (unique value
//   references per type, causality/variability combinations, start values where required),
//   and ensemble_member selecting its draw;
// * the C code compiled by the system's compiler with -std=c99 -Wall -Werror: its RK4 step on
//   the engine's interpolated inputs, its record simulation (the run's step rule and input
//   interpolation) on the record's inputs at its nodes, and its example program run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "Eigen/Dense"
#include "engine/config/config.h"
#include "engine/export/c_model.h"
#include "engine/export/model_json.h"
#include "engine/export/run_folder_model.h"
#include "engine/export/fmu_package.h"
#include "engine/export/shared_library_needs.h"
#include "engine/run/records.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "tests/support/c_model_loader.h"
#include "tests/support/fmu_loader.h"
#include "tests/support/run_command.h"
#include "tests/support/simulated_records.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VESSELID_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define VESSELID_TEST_SANITIZED 1
#endif

namespace vesselid {
namespace model_export_test {

#ifdef VESSELID_TEST_SANITIZED
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif

namespace fs = std::filesystem;

class ModelExport : public ::testing::TestWithParam<std::string> {};

// The FMI 2.0 combinations of causality and variability (table in section 2.2.7) this export
// uses, each allowed, and a start value on every input and parameter.
void CheckDescription(const testing::FmuLoader& fmu) {
  std::set<std::pair<std::string, unsigned>> references;
  std::set<std::string> names;
  for (const testing::FmuVariable& v : fmu.variables()) {
    EXPECT_TRUE(references.insert({v.type, v.reference}).second)
        << v.type << " value reference " << v.reference << " used twice";
    EXPECT_TRUE(names.insert(v.name).second) << v.name << " named twice";
    const std::string pair = v.causality + "/" + v.variability;
    EXPECT_TRUE(pair == "input/continuous" || pair == "output/continuous" ||
                pair == "parameter/tunable" || pair == "parameter/fixed")
        << v.name << ": " << pair;
  }
  const std::string& xml = fmu.description();
  EXPECT_NE(xml.find("fmiVersion=\"2.0\""), std::string::npos);
  EXPECT_NE(xml.find("<InitialUnknowns>"), std::string::npos);
  // Every input and parameter carries a start value.
  const std::regex needs_start(
      "causality=\"(input|parameter)\"[^>]*>\\s*<(Real|Integer)(?![^>]*start=)");
  EXPECT_FALSE(std::regex_search(xml, needs_start)) << xml;
}

// Worst relative difference of `got` from `expected` (nodes x outputs) over the outputs the
// model defines (NaN in both elsewhere), each relative to the larger of |expected| and a
// thousandth of its channel's largest value; `at` names where.
double WorstDifference(const std::vector<double>& expected, const std::vector<double>& got,
                       const ModelInfo& info, const std::vector<double>& node_time,
                       std::string* at) {
  const int ny = static_cast<int>(info.outputs.size());
  const int nodes = static_cast<int>(node_time.size());
  std::vector<double> scale(ny, 0.0);
  for (int k = 0; k < nodes; ++k) {
    for (int j = 0; j < ny; ++j) scale[j] = std::max(scale[j], std::abs(expected[k * ny + j]));
  }
  double worst = 0.0;
  for (int k = 0; k < nodes; ++k) {
    for (int j = 0; j < ny; ++j) {
      const double e = expected[k * ny + j], g = got[k * ny + j];
      const double relative = std::isnan(e)
                                  ? (std::isnan(g) ? 0.0 : 1.0)
                                  : std::abs(g - e) / std::max(std::abs(e), 1e-3 * scale[j]);
      if (!(relative <= worst)) {
        worst = relative;
        *at = info.outputs[j] + " at t = " + std::to_string(node_time[k]);
      }
    }
  }
  return worst;
}

// The C export of `exported` (the model of `config`'s `stage`, whose first record `e` the
// engine simulates from x0 as `reference`), built in dir/c and checked against the engine.
void CheckCModel(const RunConfig& config, const StageConfig& stage, const ModelHandle& model,
                 IdentifiedModel exported, const Experiment& e, const std::vector<double>& x0,
                 const std::vector<double>& reference, const fs::path& dir) {
  const ModelInfo& info = model.info();
  const ExperimentSpec* spec = nullptr;
  for (const ExperimentSpec& s : config.experiments) {
    if (s.name == stage.experiments.front()) spec = &s;
  }
  ASSERT_NE(spec, nullptr);
  for (size_t i = 0; i < info.inputs.size(); ++i) {
    const auto method = spec->interpolation.find(info.inputs[i]);
    exported.interpolation[i] = InterpolationToString(
        method == spec->interpolation.end() ? spec->default_interpolation : method->second);
  }
  std::vector<CModelFile> files;
  std::string error;
  ASSERT_TRUE(MakeCModel(exported, model, &files, &error)) << error;
  fs::create_directories(dir / "c");
  testing::CModelLoader c;
  const std::string id = CIdentifier(exported.model);
  ASSERT_TRUE(c.Build(files, id, (dir / "c").string(), &error)) << error;
  const double* p = exported.values.data();
  // Member 0 is the estimate, member k the k-th draw; none beyond the last.
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    EXPECT_EQ(c.member(0)[i], exported.values[i]) << info.parameters[i];
    EXPECT_EQ(c.member(2)[i], exported.ensemble[1][i]) << info.parameters[i];
  }
  EXPECT_EQ(c.member(static_cast<int>(exported.ensemble.size()) + 1), nullptr);

  // Its RK4 steps on the engine's interpolated inputs.
  const int nu = e.num_inputs, ny = static_cast<int>(info.outputs.size());
  const int nodes = e.num_nodes();
  std::vector<double> x = x0, stepped(static_cast<size_t>(nodes) * ny, NAN);
  const double* u = e.input_cache.data();
  for (int k = 0; k < nodes; ++k) {
    c.output(x.data(), u, p, stepped.data() + k * ny);
    if (k + 1 == nodes) break;
    for (int s = 0; s < e.node_substeps[k]; ++s, u += 3 * nu) {
      ASSERT_EQ(c.rk4_step(x.data(), u, u + nu, u + 2 * nu, p, e.node_step[k]), 1)
          << "at t = " << e.node_time[k];
    }
  }
  std::string at;
  double worst = WorstDifference(reference, stepped, info, e.node_time, &at);
  std::printf("%s: C steps, worst relative difference %.3g (%s)\n", id.c_str(), worst, at.c_str());
  EXPECT_LE(worst, 1e-10) << "C steps: worst " << at;

  // Its record simulation on the record's inputs at the nodes, against the engine's
  // simulation of the same samples (an in-memory record on the node grid).
  auto grid = std::make_shared<Trajectory>();
  grid->source = "grid";
  grid->t = e.node_time;
  std::vector<double> inputs(static_cast<size_t>(nodes) * nu, NAN);
  ExperimentSpec grid_spec;
  grid_spec.name = "grid";
  grid_spec.interpolation = spec->interpolation;
  grid_spec.default_interpolation = spec->default_interpolation;
  int step = 0;
  for (int k = 0; k < nodes; ++k) {
    for (int i = 0; i < nu; ++i) inputs[k * nu + i] = e.input_cache[3 * step * nu + i];
    if (k + 1 < nodes) step += e.node_substeps[k];
  }
  for (int i = 0; i < nu; ++i) {
    if (spec->inputs.count(info.inputs[i]) == 0) continue;
    grid_spec.inputs[info.inputs[i]] = info.inputs[i];
    grid->names.push_back(info.inputs[i]);
    grid->columns.emplace_back();
    for (int k = 0; k < nodes; ++k) grid->columns.back().push_back(inputs[k * nu + i]);
  }
  for (int j = 0; j < ny; ++j) {
    bool finite = true;
    for (int k = 0; k < nodes; ++k) finite = finite && std::isfinite(reference[k * ny + j]);
    if (!finite ||
        std::find(grid->names.begin(), grid->names.end(), info.outputs[j]) != grid->names.end()) {
      continue;
    }
    grid_spec.outputs[info.outputs[j]] = info.outputs[j];
    grid->names.push_back(info.outputs[j]);
    grid->columns.emplace_back();
    for (int k = 0; k < nodes; ++k) grid->columns.back().push_back(reference[k * ny + j]);
  }
  for (size_t s = 0; s < info.states.size(); ++s) grid_spec.initial_state[info.states[s]] = x0[s];
  grid_spec.table = grid;
  RunConfig grid_config = config;
  grid_config.experiments = {grid_spec};
  TrajectoryCache cache;
  std::vector<Experiment> grid_experiments;
  ASSERT_TRUE(PrepareExperiments(grid_config, {"grid"}, model, stage.experiment, &cache,
                                 &grid_experiments, &error))
      << error;
  ASSERT_EQ(grid_experiments.front().node_time, e.node_time);
  std::vector<double> grid_reference, simulated(static_cast<size_t>(nodes) * ny);
  ASSERT_TRUE(model.SimulateOutputs(grid_experiments.front(), p, x0.data(), &grid_reference));
  ASSERT_EQ(c.simulate(nodes, e.node_time.data(), inputs.data(), x0.data(), p, exported.max_step,
                       simulated.data()),
            nodes);
  worst = WorstDifference(grid_reference, simulated, info, e.node_time, &at);
  std::printf("%s: C record simulation, worst relative difference %.3g (%s)\n", id.c_str(), worst,
              at.c_str());
  EXPECT_LE(worst, 1e-10) << "C simulation: worst " << at;

  // The example runs and prints every output.
  const testing::CommandOutcome example = testing::RunCommand(c.example());
  EXPECT_EQ(example.status, 0) << example.output;
  for (const std::string& output : info.outputs) {
    EXPECT_NE(example.output.find(output), std::string::npos) << example.output;
  }
}

TEST_P(ModelExport, FmuAndCReproduceTheEnginesSimulationOfTheFirstRecord) {
  const std::string name = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("vesselid_fmu_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string config_path = std::string(VESSELID_SOURCE_DIR) + "/configs/" + name + ".yaml";
  const fs::path data = testing::SimulatedRecords(name);
  ASSERT_FALSE(data.empty()) << "vesselid simulate " << config_path;
  const ModelRegistry registry = DefaultRegistry();
  RunConfig config;
  std::string error;
  ASSERT_TRUE(LoadRunConfig(config_path, data.string(), registry, &config, &error)) << error;
  // The model of the first output-error stage, at its parameters' starts (the model's typical
  // values where a start is an earlier stage's estimate).
  const StageConfig* stage = nullptr;
  for (const StageConfig& s : config.stages) {
    if (stage == nullptr && s.kind == StageConfig::Kind::kOutputError) stage = &s;
  }
  ASSERT_NE(stage, nullptr);
  IdentifiedModel exported;
  const std::shared_ptr<const ModelHandle> model = MakeIdentifiedModel(
      registry, config.family, config.StageModelOptions(*stage), &exported, &error);
  ASSERT_NE(model, nullptr) << error;
  const ModelInfo& info = model->info();
  for (const ParameterSpec& p : stage->parameters) {
    if (p.start_from_previous) continue;
    for (size_t i = 0; i < info.parameters.size(); ++i) {
      if (info.parameters[i] == p.name) exported.values[i] = p.start;
    }
  }
  exported.max_step = stage->experiment.max_step;
  // Two draws of 1 % spread in every parameter.
  exported.covariance_names = info.parameters;
  exported.covariance = Eigen::MatrixXd::Zero(info.parameters.size(), info.parameters.size());
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    exported.covariance(i, i) = std::pow(0.01 * exported.values[i], 2);
  }
  exported.ensemble = DrawEnsemble(exported, 2, 7);

  // The engine's simulation of the stage's first record.
  TrajectoryCache cache;
  std::vector<Experiment> experiments;
  ASSERT_TRUE(PrepareExperiments(config, {stage->experiments.front()}, *model, stage->experiment,
                                 &cache, &experiments, &error))
      << error;
  const Experiment& e = experiments.front();
  // The same record in steps of a third of its shortest sample interval or less: its input
  // cache holds each input's interpolant at four points or more of every interval.
  ExperimentOptions fine_options = stage->experiment;
  double shortest = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < e.num_nodes(); ++k) {
    shortest = std::min(shortest, e.node_time[k + 1] - e.node_time[k]);
  }
  fine_options.max_step = shortest / 3.0;
  std::vector<Experiment> fine_experiments;
  ASSERT_TRUE(PrepareExperiments(config, {stage->experiments.front()}, *model, fine_options, &cache,
                                 &fine_experiments, &error))
      << error;
  const Experiment& fine = fine_experiments.front();
  ASSERT_EQ(fine.node_time, e.node_time);
  // The record's first state as a stage with free initial states starts from it: the guess
  // from the outputs and their rates (an MMG ship's surge speed from its track), else the
  // measured or given value.
  std::vector<double> x0 = e.initial_state.empty() ? e.initial_state_guess : e.initial_state;
  for (size_t s = 0; s < x0.size() && s < e.initial_state_guess.size(); ++s) {
    if (std::isfinite(e.initial_state_guess[s])) x0[s] = e.initial_state_guess[s];
  }
  std::vector<double> reference;
  ASSERT_TRUE(model->SimulateOutputs(e, exported.values.data(), x0.data(), &reference))
      << ::testing::PrintToString(x0);

  ASSERT_TRUE(WriteFmu(exported, VESSELID_FMU_RUNTIME, (dir / "model.fmu").string(), &error))
      << error;
  testing::FmuLoader fmu;
  ASSERT_TRUE(fmu.Open((dir / "model.fmu").string(), (dir / "unpacked").string(), &error)) << error;
  CheckDescription(fmu);
  EXPECT_STREQ(fmu.Version(), "2.0");
  ASSERT_TRUE(fmu.Instantiate());
  const int nu = e.num_inputs, ny = static_cast<int>(info.outputs.size());
  std::vector<int> input(nu), output(ny);
  for (int i = 0; i < nu; ++i) input[i] = fmu.Reference(info.inputs[i]);
  for (int j = 0; j < ny; ++j) output[j] = fmu.Reference(info.outputs[j]);
  ASSERT_EQ(fmu.Setup(e.node_time.front()), fmi2OK);
  ASSERT_EQ(fmu.EnterInitialization(), fmi2OK);
  for (size_t s = 0; s < info.states.size(); ++s) {
    ASSERT_EQ(fmu.SetReal(fmu.Reference("initial_" + info.states[s]), x0[s]), fmi2OK);
  }
  ASSERT_EQ(fmu.ExitInitialization(), fmi2OK);

  // Per node: the inputs at its time and their interpolant's derivatives there (the cubic in
  // tau through the fine cache's step starts 0, h/m, 2 h/m and the interval's end, a left
  // limit: exact for the run's hold, linear and cubic interpolations), the outputs, one step.
  const int nodes = e.num_nodes();
  std::vector<double> channel_scale(ny, 0.0);
  for (int k = 0; k < nodes; ++k) {
    for (int j = 0; j < ny; ++j) {
      channel_scale[j] = std::max(channel_scale[j], std::abs(reference[k * ny + j]));
    }
  }
  int step = 0, fine_step = 0;
  double worst = 0.0;
  std::string worst_at;
  for (int k = 0; k < nodes; ++k) {
    const double* start = e.input_cache.data() + 3 * step * nu;
    const int substeps = k + 1 < nodes ? e.node_substeps[k] : 0;
    for (int i = 0; i < nu; ++i) {
      ASSERT_EQ(fmu.SetReal(input[i], start[i]), fmi2OK);
      if (substeps == 0 || !std::isfinite(start[i])) continue;
      const int m = fine.node_substeps[k];
      ASSERT_GE(m, 3);
      const double h = e.node_time[k + 1] - e.node_time[k];
      Eigen::Matrix4d powers;
      Eigen::Vector4d values;
      const double points[4] = {0.0, 1.0 / m, 2.0 / m, 1.0};
      const int rows[4] = {3 * fine_step, 3 * (fine_step + 1), 3 * (fine_step + 2),
                           3 * (fine_step + m - 1) + 2};
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) powers(r, c) = std::pow(points[r], c);
        values[r] = fine.input_cache[rows[r] * nu + i];
      }
      const Eigen::Vector4d c = powers.fullPivLu().solve(values);  // in s = tau / h
      ASSERT_EQ(fmu.SetDerivative(input[i], 1, c[1] / h), fmi2OK);
      ASSERT_EQ(fmu.SetDerivative(input[i], 2, 2.0 * c[2] / (h * h)), fmi2OK);
      ASSERT_EQ(fmu.SetDerivative(input[i], 3, 6.0 * c[3] / (h * h * h)), fmi2OK);
    }
    for (int j = 0; j < ny; ++j) {
      const double expected = reference[k * ny + j], got = fmu.GetReal(output[j]);
      // An output the model leaves undefined (NaN, e.g. of an input the record lacks) is so in
      // both.
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(got)) << info.outputs[j] << " at t = " << e.node_time[k];
        continue;
      }
      const double relative =
          std::abs(got - expected) / std::max(std::abs(expected), 1e-3 * channel_scale[j]);
      if (!(relative <= worst)) {
        worst = relative;
        worst_at = info.outputs[j] + " at t = " + std::to_string(e.node_time[k]);
      }
    }
    if (substeps == 0) break;
    ASSERT_EQ(fmu.DoStep(e.node_time[k], e.node_time[k + 1] - e.node_time[k]), fmi2OK)
        << "at t = " << e.node_time[k];
    step += substeps;
    fine_step += fine.node_substeps[k];
  }
  std::printf("%s: %d nodes, worst relative difference %.3g (%s)\n", name.c_str(), nodes, worst,
              worst_at.c_str());
  EXPECT_LE(worst, 1e-10) << name << ": worst " << worst_at << " over " << nodes << " nodes";
  EXPECT_EQ(fmu.Terminate(), fmi2OK);

  // ensemble_member 2 sets every parameter to the second draw.
  testing::FmuLoader member;
  ASSERT_TRUE(member.Open((dir / "model.fmu").string(), (dir / "member").string(), &error));
  ASSERT_TRUE(member.Instantiate());
  ASSERT_EQ(member.EnterInitialization(), fmi2OK);
  ASSERT_EQ(member.SetInteger(member.Reference("ensemble_member"), 2), fmi2OK);
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    EXPECT_EQ(member.GetReal(member.Reference(info.parameters[i])), exported.ensemble[1][i])
        << info.parameters[i];
  }
  EXPECT_NE(member.SetInteger(member.Reference("ensemble_member"), 3), fmi2OK);

  // A parameter the master sets to a value of its own keeps it, before or after
  // ensemble_member (fmpy sets start values in modelDescription order: parameters first); set
  // to its start value (a master applying every start value) it takes the draw.
  const std::string& chosen = info.parameters.front();
  const double own = exported.values.front() * 1.5 + 0.1;
  for (bool before : {true, false}) {
    SCOPED_TRACE(before ? "set before ensemble_member" : "set after ensemble_member");
    testing::FmuLoader order;
    ASSERT_TRUE(order.Open((dir / "model.fmu").string(), (dir / "order").string(), &error));
    ASSERT_TRUE(order.Instantiate());
    for (size_t i = 1; i < info.parameters.size(); ++i) {
      ASSERT_EQ(order.SetReal(order.Reference(info.parameters[i]), exported.values[i]), fmi2OK);
    }
    if (before) ASSERT_EQ(order.SetReal(order.Reference(chosen), own), fmi2OK);
    ASSERT_EQ(order.SetInteger(order.Reference("ensemble_member"), 2), fmi2OK);
    if (!before) ASSERT_EQ(order.SetReal(order.Reference(chosen), own), fmi2OK);
    EXPECT_EQ(order.GetReal(order.Reference(chosen)), own);
    for (size_t i = 1; i < info.parameters.size(); ++i) {
      EXPECT_EQ(order.GetReal(order.Reference(info.parameters[i])), exported.ensemble[1][i])
          << info.parameters[i];
    }
  }

  CheckCModel(config, *stage, *model, exported, e, x0, reference, dir);
  fs::remove_all(dir);
}

// VESSELID_FMU_RUNTIME names the runtime the FMU packs: a file, or a clear refusal (a folder
// given there once aborted the export on an uncaught stream error).
TEST(FmuRuntime, TheVariableNamesAFileOrIsRefused) {
  std::string error;
  ASSERT_EQ(setenv("VESSELID_FMU_RUNTIME", VESSELID_FMU_RUNTIME, 1), 0);
  EXPECT_EQ(FindFmuRuntime(&error), VESSELID_FMU_RUNTIME) << error;
  const fs::path folder = fs::temp_directory_path();
  ASSERT_EQ(setenv("VESSELID_FMU_RUNTIME", folder.c_str(), 1), 0);
  EXPECT_EQ(FindFmuRuntime(&error), "");
  EXPECT_EQ(error, "VESSELID_FMU_RUNTIME: " + folder.string() + ": not a file");
  ASSERT_EQ(setenv("VESSELID_FMU_RUNTIME", (folder / "no_such_runtime.so").c_str(), 1), 0);
  EXPECT_EQ(FindFmuRuntime(&error), "");
  EXPECT_NE(error.find(": no such file"), std::string::npos) << error;
  unsetenv("VESSELID_FMU_RUNTIME");
}

// `vesselid export` on a finished run (the tanker's n1-form Nomoto model): the C files are
// written beside; model.json holds the run's final values, the covariance of its estimates
// (diagonal: their squared standard errors) and 100 draws around the values; the FMU starts its
// parameters at the final values and offers the draws; bad requests are refused with one clear line
// and nothing written.
TEST(ExportCommand, TakesARunsModelOutAsJsonAndFmu) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_export_command";
  fs::remove_all(dir);
  const std::string binary = VESSELID_BINARY;
  const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
  ASSERT_EQ(std::system((binary + " simulate " + config + " --out " + (dir / "data").string() +
                         " > /dev/null")
                            .c_str()),
            0);
  ASSERT_EQ(std::system((binary + " run " + config + " --data " + (dir / "data").string() +
                         " --out " + (dir / "run").string() + " --quiet --no-report > /dev/null")
                            .c_str()),
            0);
  const std::string run = (dir / "run").string();
  ASSERT_EQ(std::system((binary + " export " + run + " --format json > /dev/null").c_str()), 0);
  ASSERT_EQ(std::system((binary + " export " + run + " --format fmu > /dev/null").c_str()), 0);
  ASSERT_EQ(std::system((binary + " export " + run + " --format c > /dev/null").c_str()), 0);
  std::ifstream results_file(dir / "run" / "results.json");
  const nlohmann::json results = nlohmann::json::parse(results_file);
  const std::string model_name = results["model"]["name"];
  for (const char* file : {".h", ".c", "_example.c"}) {
    EXPECT_TRUE(fs::exists(dir / "run" / "export" / (model_name + file))) << file;
  }
  std::ifstream model_file(dir / "run" / "export" / (model_name + ".json"));
  const nlohmann::json model = nlohmann::json::parse(model_file);
  EXPECT_EQ(model["family"], "nomoto");
  EXPECT_EQ(model["options"], results["model"]["options"]);
  std::map<std::string, double> value, std_error;
  for (const nlohmann::json& p : results["parameters"]) {
    // The run's bias per zigzag (delta_0, per experiment): its value in results.json is the
    // training runs' mean, and the export takes it as every other use of the results does.
    value[p["name"]] = p["value"].get<double>();
    if (p["std_error"].is_number()) std_error[p["name"]] = p["std_error"];
  }
  ASSERT_EQ(value.count("delta_0"), 1u);
  std::vector<std::string> names;
  for (const nlohmann::json& p : model["parameters"]) {
    names.push_back(p["name"]);
    EXPECT_EQ(p["value"].get<double>(), value.at(p["name"])) << p["name"];
  }
  const std::vector<std::string> estimated = model["covariance"]["names"];
  ASSERT_FALSE(estimated.empty());
  for (size_t a = 0; a < estimated.size(); ++a) {
    const double se = std_error.at(estimated[a]);
    EXPECT_NEAR(model["covariance"]["matrix"][a][a].get<double>(), se * se, 1e-12 * se * se);
  }
  // The draws: 100, centred on the values within 4 standard errors of their mean.
  const nlohmann::json& members = model["ensemble"]["members"];
  ASSERT_EQ(members.size(), 100u);
  for (const std::string& name : estimated) {
    const size_t i = std::find(names.begin(), names.end(), name) - names.begin();
    double mean = 0.0;
    for (const nlohmann::json& m : members) mean += m[i].get<double>() / 100.0;
    EXPECT_NEAR(mean, value[name], 4.0 * std_error[name] / 10.0) << name;
  }

  testing::FmuLoader fmu;
  std::string error;
  ASSERT_TRUE(fmu.Open((dir / "run" / "export" / (model_name + ".fmu")).string(),
                       (dir / "unpacked").string(), &error))
      << error;
  EXPECT_NE(fmu.description().find("max=\"100\""), std::string::npos);
  ASSERT_TRUE(fmu.Instantiate());
  for (const std::string& name : names) {
    EXPECT_EQ(fmu.GetReal(fmu.Reference(name)), value[name]) << name;
  }
  // The binary needs nothing from the host but the C and C++ runtimes and yaml-cpp (no solver,
  // no MPI, no SuiteSparse), and its documentation says so.
  std::vector<std::string> needs;
  ASSERT_TRUE(SharedLibraryNeeds(
      (dir / "unpacked" / "binaries" / "linux64" / "vesselid_model.so").string(), &needs, &error))
      << error;
  const std::set<std::string> allowed = {"libyaml-cpp.so.0.7", "libstdc++.so.6", "libm.so.6",
                                         "libgcc_s.so.1",      "libc.so.6",      "ld-linux-x86-64.so.2"};
  std::ifstream documentation_file(dir / "unpacked" / "documentation" / "index.html");
  const std::string documentation((std::istreambuf_iterator<char>(documentation_file)),
                                  std::istreambuf_iterator<char>());
  for (const std::string& library : needs) {
    // The sanitizers' instrumentation keeps every object alive: only the release runtime sheds
    // the solver libraries.
    if (!kSanitized) EXPECT_EQ(allowed.count(library), 1u) << library;
    EXPECT_NE(documentation.find("<code>" + library + "</code>"), std::string::npos) << library;
  }
  EXPECT_NE(documentation.find("Runtime dependencies"), std::string::npos);

  // A run whose covariance is a bootstrap's carries its replicates: the ensemble is theirs.
  nlohmann::json boot = results;
  nlohmann::json* correlated = nullptr;
  for (nlohmann::json& stage : boot["stages"]) {
    if (stage.contains("correlation")) correlated = &stage;
  }
  ASSERT_NE(correlated, nullptr);
  nlohmann::json replicate_values = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (size_t a = 0; a < estimated.size(); ++a) row.push_back(value[estimated[a]] + r + 1.0);
    replicate_values.push_back(row);
  }
  (*correlated)["uncertainty"]["replicates"] = {{"names", estimated}, {"values", replicate_values}};
  fs::create_directories(dir / "boot");
  std::ofstream(dir / "boot" / "results.json") << boot.dump();
  ASSERT_EQ(
      std::system(
          (binary + " export " + (dir / "boot").string() + " --format json > /dev/null").c_str()),
      0);
  std::ifstream boot_file(dir / "boot" / "export" / (model_name + ".json"));
  const nlohmann::json boot_model = nlohmann::json::parse(boot_file);
  EXPECT_EQ(boot_model["ensemble"]["source"], "bootstrap");
  ASSERT_EQ(boot_model["ensemble"]["members"].size(), 3u);
  for (size_t a = 0; a < estimated.size(); ++a) {
    const size_t i = std::find(names.begin(), names.end(), estimated[a]) - names.begin();
    EXPECT_EQ(boot_model["ensemble"]["members"][2][i].get<double>(), value[estimated[a]] + 3.0);
  }

  // Refused: not a run's folder, an unknown format, a negative ensemble; nothing written.
  auto refused = [&](const std::string& arguments, const std::string& says) {
    const std::string command = binary + " export " + arguments;
    const testing::CommandOutcome outcome = testing::RunCommand(command);
    EXPECT_NE(outcome.status, 0) << command;
    EXPECT_NE(outcome.output.find(says), std::string::npos) << command << "\n" << outcome.output;
  };
  refused((dir / "data").string() + " --format json", "results.json: cannot open");
  refused(run + " --format onnx", "--format");
  refused(run + " --members -3 --out " + (dir / "neg").string(), "--members must be >= 0");
  EXPECT_FALSE(fs::exists(dir / "data" / "export"));
  EXPECT_FALSE(fs::exists(dir / "neg"));
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Shipped, ModelExport,
                         ::testing::Values("nomoto_cargo", "nomoto_cargo_noise", "nomoto_patrol",
                                           "nomoto_patrol_noise", "nomoto_tanker", "eriksen_2dof",
                                           "erunsal_hierarchy", "input_gain_static",
                                           "input_gain_dynamic", "input_gain_usv_log",
                                           "mmg_kvlcc2"));

}  // namespace model_export_test
}  // namespace vesselid
