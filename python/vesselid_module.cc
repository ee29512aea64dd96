// vesselid._core: the engine's entry points for the Python package (python/vesselid/).
// The package passes configs as text or paths and records as columns of float64 arrays; the
// results come back as results.json's text, so Result.to_json() is results.json exactly.
// Every entry point returns (ok, kind, message, payload): kind names the error class the
// package raises ("config", "data", "run", "interrupted").
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "engine/base/stop_request.h"
#include "engine/config/config.h"
#include "engine/data/trajectory_table.h"
#include "engine/design/design_config.h"
#include "engine/design/design_report.h"
#include "engine/design/design_run.h"
#include "engine/diagnose/run_findings.h"
#include "engine/export/export_run.h"
#include "engine/model/open_loop_simulation.h"
#include "engine/output/output_folder.h"
#include "engine/output/results_json_text.h"
#include "engine/output/results_text.h"
#include "engine/output/run_traces.h"
#include "engine/report/results_writer.h"
#include "engine/run/pipeline.h"
#include "engine/study/study.h"
#include "problems/registry.h"
#include "yaml-cpp/yaml.h"

namespace py = pybind11;

namespace vesselid {
namespace {

using Outcome = std::tuple<bool, std::string, std::string, std::string>;

Outcome Failure(const std::string& kind, const std::string& message) {
  return {false, kind, message, ""};
}

const ModelRegistry& Registry() {
  static const ModelRegistry registry = DefaultRegistry();
  return registry;
}

// A record's columns: {name: float64 array}; the arrays are copied (the engine keeps its
// own record while the run lasts, and the caller's frame may change meanwhile).
std::shared_ptr<Trajectory> TableFromColumns(const std::string& experiment,
                                             const py::dict& columns) {
  auto table = std::make_shared<Trajectory>();
  table->source = "experiment '" + experiment + "' (data given)";
  for (const auto& [key, value] : columns) {
    table->names.push_back(py::cast<std::string>(key));
    const auto array =
        py::cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(value);
    if (array.ndim() != 1) {
      throw std::invalid_argument(table->source + ": column '" + table->names.back() +
                                  "' is not one-dimensional");
    }
    table->columns.emplace_back(array.data(), array.data() + array.shape(0));
  }
  return table;
}

// A record as {name: float64 array}, time first as "t" (the arrays copied).
py::dict ColumnsOf(const Trajectory& record) {
  py::dict columns;
  columns["t"] = py::array_t<double>(record.t.size(), record.t.data());
  for (size_t c = 0; c < record.names.size(); ++c) {
    columns[py::str(record.names[c])] =
        py::array_t<double>(record.columns[c].size(), record.columns[c].data());
  }
  return columns;
}

// Loads a config (text or path) with the given records attached; kind "config" or "data" on
// failure.
Outcome LoadWithData(const std::string& config, bool is_text, const std::string& name,
                     const std::string& data_dir, const py::dict& data, ConfigFile* file) {
  ConfigSource source;
  source.path = is_text ? name : config;
  if (is_text) source.text = config;
  source.data_dir = data_dir;
  for (const auto& [key, value] : data) source.in_memory.insert(py::cast<std::string>(key));
  std::string error;
  if (!LoadConfig(source, Registry(), file, &error)) return Failure("config", error);
  // One table per columns object: experiments given the same one share its record.
  std::map<const PyObject*, std::shared_ptr<const Trajectory>> tables;
  for (const auto& [key, value] : data) {
    const std::string experiment = py::cast<std::string>(key);
    ExperimentSpec* spec = nullptr;
    for (ExperimentSpec& s : file->run.experiments) {
      if (s.name == experiment) spec = &s;
    }
    if (spec == nullptr) {
      return Failure(
          "data", "data given for '" + experiment + "', which is not an experiment of the config");
    }
    std::shared_ptr<const Trajectory>& table = tables[value.ptr()];
    try {
      if (table == nullptr) table = TableFromColumns(experiment, py::cast<py::dict>(value));
    } catch (const std::exception& e) {
      return Failure("data", e.what());
    }
    spec->table = table;
    // The table's own checks now, so that a bad frame is a data error before any stage.
    Trajectory checked;
    CsvReadOptions options = spec->csv;
    options.columns.clear();
    if (!TrajectoryFromTable(*spec->table, options, &checked, &error)) {
      return Failure("data", error);
    }
  }
  return {true, "", "", ""};
}

// Whether a run's error is about its data: it names a record (a file or a given table).
bool AboutData(const RunConfig& config, const std::string& error) {
  for (const ExperimentSpec& spec : config.experiments) {
    if (!spec.file.empty() && error.find(spec.file) != std::string::npos) return true;
    if (spec.table && error.find(spec.table->source) != std::string::npos) return true;
  }
  return false;
}

// The run's outcome, and on success its traces: {"<stage>.<experiment>": columns}
// (run_traces.h).
Outcome RunStages(const std::string& config, bool is_text, const std::string& name,
                  const std::string& data_dir, const py::dict& data, const std::string& out_dir,
                  bool write_report, int threads, const py::object& progress, py::dict* traces) {
  ConfigFile file;
  const Outcome loaded = LoadWithData(config, is_text, name, data_dir, data, &file);
  if (!std::get<0>(loaded)) return loaded;
  // The same results on any number of threads (thread_count_test.cc); 0 keeps the config's.
  if (threads > 0) {
    for (StageConfig& stage : file.run.stages) {
      stage.options.local.num_threads = threads;
      stage.options.global.threads = threads;
    }
  }
  const RunConfig& run = file.run;
  std::string error;
  std::unique_ptr<OutputFolder> folder;
  if (!out_dir.empty()) {
    if (!CheckInputsSurvive(out_dir, RunOutputs(run), RunInputs(run, !is_text), &error)) {
      return Failure("run", error);
    }
    folder = OutputFolder::Open(out_dir, &error);
    if (folder == nullptr) return Failure("run", error);
  }
  bool interrupted = false;
  RunObserver observer;
  // Python is called with the GIL held; a pending Ctrl-C stops the run after the stage.
  // Ctrl-C reaches Python's handler on the main thread, which runs the solves' callbacks:
  // the request ends the current solve after its iteration (stop_request.h).
  observer.progress = [&](const SolveProgress& p) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();
      interrupted = true;
      RequestStop();
      return;
    }
    if (progress.is_none()) return;
    try {
      progress(
          py::dict(py::arg("phase") = p.phase == SolveProgress::Phase::kGlobal ? "global" : "local",
                   py::arg("iteration") = p.iteration, py::arg("cost") = p.cost));
    } catch (const py::error_already_set&) {
      interrupted = true;
      RequestStop();
    }
  };
  observer.stage_finished = [&](size_t, const StageResult&, std::string* message) {
    if (!interrupted) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();
        interrupted = true;
      }
    }
    if (interrupted) *message = "interrupted";
    return !interrupted;
  };
  RunResult result;
  bool complete = false;
  ClearStopRequest();
  {
    py::gil_scoped_release release;
    complete = Identify(run, &result, &error, observer);
  }
  ClearStopRequest();
  if (interrupted) return Failure("interrupted", "the run was interrupted");
  if (!complete && result.stages.empty()) {
    return Failure(AboutData(run, error) ? "data" : "run", error);
  }
  if (folder != nullptr && !WriteRunResults(run, result, out_dir, &error, write_report)) {
    return Failure("run", error);
  }
  if (!complete) {
    return Failure("run", "the run stopped in stage '" + result.stopped_stage + "': " + error);
  }
  for (const NamedTrace& trace : RunTraces(run, result)) {
    (*traces)[py::str(trace.name)] = ColumnsOf(trace.trace);
  }
  return {true, "", RunResultToText(run, result), RunResultJsonText(run, result, -1)};
}

py::tuple Run(const std::string& config, bool is_text, const std::string& name,
              const std::string& data_dir, const py::dict& data, const std::string& out_dir,
              bool write_report, int threads, const py::object& progress) {
  py::dict traces;
  const auto [ok, kind, message, payload] = RunStages(config, is_text, name, data_dir, data,
                                                      out_dir, write_report, threads, progress,
                                                      &traces);
  return py::make_tuple(ok, kind, message, payload, traces);
}

// A config loaded without its records (every experiment may come as a frame): the run's
// model and every check a run makes of the config.
bool LoadModelOnly(const std::string& config, bool is_text, const std::string& name,
                   ConfigFile* file, std::string* error) {
  ConfigSource source;
  source.path = is_text ? name : config;
  if (is_text) source.text = config;
  try {
    const YAML::Node root = is_text ? YAML::Load(config) : YAML::LoadFile(config);
    if (root["experiments"] && root["experiments"].IsSequence()) {
      for (const YAML::Node& e : root["experiments"]) {
        if (e.IsMap() && e["name"] && e["name"].IsScalar())
          source.in_memory.insert(e["name"].Scalar());
      }
    }
  } catch (const YAML::Exception&) {
    // LoadConfig names the syntax error with its line.
  }
  return LoadConfig(source, Registry(), file, error);
}

// Checks a config file as a run would (every key, names, bounds) without its records, which
// a notebook may pass as frames.
Outcome CheckConfig(const std::string& path) {
  ConfigFile file;
  std::string error;
  if (!LoadModelOnly(path, false, path, &file, &error)) return Failure("config", error);
  return {true, "", "", ""};
}

// The model's names, units and default parameters, as a dict.
py::tuple ModelInfoOf(const std::string& config, bool is_text, const std::string& name) {
  ConfigFile file;
  std::string error;
  if (!LoadModelOnly(config, is_text, name, &file, &error)) {
    return py::make_tuple(false, "config", error, py::none());
  }
  const ModelInfo& info = file.run.model->info();
  std::vector<std::string> input_units, output_units, state_units, parameter_units;
  for (size_t i = 0; i < info.inputs.size(); ++i) input_units.push_back(info.InputUnit(i));
  for (size_t i = 0; i < info.outputs.size(); ++i) output_units.push_back(info.OutputUnit(i));
  for (size_t i = 0; i < info.states.size(); ++i) state_units.push_back(info.StateUnit(i));
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    parameter_units.push_back(info.ParameterUnit(i));
  }
  py::dict d;
  d["name"] = info.name;
  d["family"] = file.run.family;
  d["inputs"] = info.inputs;
  d["outputs"] = info.outputs;
  d["states"] = info.states;
  d["parameters"] = info.parameters;
  d["defaults"] = info.parameter_defaults;
  d["input_units"] = input_units;
  d["output_units"] = output_units;
  d["state_units"] = state_units;
  d["parameter_units"] = parameter_units;
  return py::make_tuple(true, "", "", d);
}

// The run's model simulated open loop (open_loop_simulation.h) under `inputs` ({"t": times,
// input: values}, SI units), from `initial_state` with `parameters` (model order, SI).
py::tuple SimulateModel(const std::string& config, bool is_text, const std::string& name,
                        const std::vector<double>& parameters,
                        const std::vector<double>& initial_state, const py::dict& inputs,
                        int substeps, const std::string& interpolation) {
  ConfigFile file;
  std::string error;
  if (!LoadModelOnly(config, is_text, name, &file, &error)) {
    return py::make_tuple(false, "config", error, py::none());
  }
  std::shared_ptr<Trajectory> table;
  try {
    table = TableFromColumns("inputs", inputs);
  } catch (const std::exception& e) {
    return py::make_tuple(false, "data", e.what(), py::none());
  }
  table->source = "inputs";
  Trajectory record;
  if (!TrajectoryFromTable(*table, CsvReadOptions(), &record, &error)) {
    return py::make_tuple(false, "data", error, py::none());
  }
  OpenLoopOptions options;
  options.substeps = substeps;
  options.record_states = true;
  if (!StringToInterpolation(interpolation, &options.interpolation)) {
    return py::make_tuple(
        false, "data",
        "unknown interpolation '" + interpolation + "' (zero_order_hold, linear, cubic)",
        py::none());
  }
  Trajectory result;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = SimulateOpenLoop(*file.run.model, parameters, initial_state, record, options, &result,
                          &error);
  }
  if (!ok) return py::make_tuple(false, "run", error, py::none());
  return py::make_tuple(true, "", "", ColumnsOf(result));
}

// `vesselid simulate`: the config's synthetic experiments written into out_dir.
Outcome Simulate(const std::string& config, bool is_text, const std::string& name,
                 const std::string& out_dir) {
  ConfigFile file;
  std::string error;
  if (!LoadModelOnly(config, is_text, name, &file, &error)) return Failure("config", error);
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = SimulateConfig(file, out_dir, &error);
  }
  if (!ok) return Failure(error.find(name) == 0 ? "config" : "run", error);
  return {true, "", "", ""};
}

// `vesselid study`: the config's study section on its records (files or given tables);
// payload: study.json's text, message: study.txt's.
Outcome Study(const std::string& config, bool is_text, const std::string& name,
              const std::string& data_dir, const py::dict& data,
              const std::vector<std::string>& only, int threads, const py::object& progress) {
  ConfigFile file;
  const Outcome loaded = LoadWithData(config, is_text, name, data_dir, data, &file);
  if (!std::get<0>(loaded)) return loaded;
  if (threads > 0) file.study.execution.threads = threads;
  std::string result, text, error;
  auto line = [&](const std::string& message) {
    if (progress.is_none()) return;
    py::gil_scoped_acquire gil;
    try {
      progress(message);
    } catch (const py::error_already_set&) {
      // A failing callback does not stop the study.
    }
  };
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = RunStudy(file.run, file.study, only, &result, &text, &error, line);
  }
  if (!ok) return Failure(AboutData(file.run, error) ? "data" : "run", error);
  return {true, "", text, result};
}

// `vesselid export`: the written file's path. The FMU runtime is the one built with this
// package unless VESSELID_FMU_RUNTIME names another.
Outcome ExportModel(const std::string& run_dir, const std::string& format,
                    const std::string& out_dir, int members, unsigned seed) {
  std::string error, path;
  std::string runtime = VESSELID_FMU_RUNTIME_BUILT;
  if (const char* given = std::getenv("VESSELID_FMU_RUNTIME")) runtime = given;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = ExportRun(Registry(), run_dir, format, out_dir, members, seed, runtime, &path, &error);
  }
  if (!ok) return Failure("run", error);
  return {true, "", "", path};
}

// `vesselid predict`: predictions.txt's text and predictions.json's.
Outcome PredictModel(const std::string& run_dir, double length, double speed, int members,
                     unsigned seed, bool write, const std::string& out_dir) {
  ManoeuvreConditions conditions;
  conditions.length = length;
  conditions.speed = speed;
  std::string error, text;
  nlohmann::json predictions;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = PredictRun(Registry(), run_dir, conditions, members, seed, write, out_dir, &predictions,
                    &text, &error);
  }
  if (!ok) return Failure("run", error);
  return {true, "", text, predictions.dump()};
}

// `vesselid design`: design.txt's text, design.json's, and the planned and predicted CSVs'.
std::tuple<bool, std::string, std::string, std::string, std::string, std::string> Design(
    const std::string& config, bool is_text, const std::string& name, const std::string& run_dir,
    bool write, const std::string& out_dir, int threads) {
  DesignOptions options;
  DesignResult result;
  std::string error;
  if (!LoadDesign(is_text ? name : config, &options, &error, is_text ? config : "")) {
    return {false, "config", error, "", "", ""};
  }
  if (threads > 0) options.threads = threads;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = PlanNextExperiment(Registry(), options, run_dir, &result, &error) &&
         (!write || WriteDesign(result, out_dir, &error));
  }
  if (!ok) return {false, "run", error, "", "", ""};
  return {true,
          "",
          DesignText(result),
          DesignToJson(result).dump(),
          PlannedInputCsv(result),
          PredictedCsv(result)};
}

}  // namespace
}  // namespace vesselid

PYBIND11_MODULE(_core, m) {
  m.def("design", &vesselid::Design, py::arg("config"), py::arg("is_text"), py::arg("name"),
        py::arg("run_dir"), py::arg("write"), py::arg("out_dir"), py::arg("threads"));
  m.doc() = "vesselid engine entry points (use the vesselid package)";
  m.def("run", &vesselid::Run, py::arg("config"), py::arg("is_text"), py::arg("name"),
        py::arg("data_dir"), py::arg("data"), py::arg("out_dir"), py::arg("write_report"),
        py::arg("threads"), py::arg("progress"));
  m.def("check_config", &vesselid::CheckConfig, py::arg("path"));
  m.def("simulate", &vesselid::Simulate, py::arg("config"), py::arg("is_text"), py::arg("name"),
        py::arg("out_dir"));
  m.def("study", &vesselid::Study, py::arg("config"), py::arg("is_text"), py::arg("name"),
        py::arg("data_dir"), py::arg("data"), py::arg("only"), py::arg("threads"),
        py::arg("progress"));
  m.def("model_info", &vesselid::ModelInfoOf, py::arg("config"), py::arg("is_text"),
        py::arg("name"));
  m.def("simulate_model", &vesselid::SimulateModel, py::arg("config"), py::arg("is_text"),
        py::arg("name"), py::arg("parameters"), py::arg("initial_state"), py::arg("inputs"),
        py::arg("substeps"), py::arg("interpolation"));
  m.def("export_model", &vesselid::ExportModel, py::arg("run_dir"), py::arg("format"),
        py::arg("out_dir"), py::arg("members"), py::arg("seed"));
  m.def("predict", &vesselid::PredictModel, py::arg("run_dir"), py::arg("length"), py::arg("speed"),
        py::arg("members"), py::arg("seed"), py::arg("write"), py::arg("out_dir"));
}
