// The commands as Python calls them: the same calls the `vesselid` program makes
// (engine/command/), with configs as text or paths and records as columns of float64 arrays.
// Errors raise the package's classes (errors.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <map>

#include "engine/base/stop_request.h"
#include "engine/command/design_command.h"
#include "engine/command/run_command.h"
#include "engine/command/select_command.h"
#include "engine/command/simulate_command.h"
#include "engine/command/study_command.h"
#include "engine/config/config.h"
#include "engine/data/trajectory_table.h"
#include "engine/design/design_report.h"
#include "engine/export/export_run.h"
#include "engine/output/results_json_text.h"
#include "engine/output/zigzag_report.h"
#include "engine/output/results_text.h"
#include "problems/registry.h"
#include "python/bind/errors.h"
#include "python/bind/frames.h"
#include "python/bind/types.h"
#include "yaml-cpp/yaml.h"

namespace vesselid::python {
namespace {

const ModelRegistry& Registry() {
  static const ModelRegistry registry = DefaultRegistry();
  return registry;
}

// A config as the package passes it: a path, or its text (a dict as JSON) named `name`.
struct ConfigArgument {
  std::string config;
  bool is_text = false;
  std::string name;
  ConfigSource Source(const std::string& data_dir, const py::dict& data) const {
    ConfigSource source;
    source.path = is_text ? name : config;
    if (is_text) source.text = config;
    source.data_dir = data_dir;
    for (const auto& [key, value] : data) source.in_memory.insert(py::str(key));
    return source;
  }
};

// The given records attached to the config's experiments (one table per columns object:
// experiments given the same one share its record), each checked now, so that a bad frame is
// a data error before any stage.
void AttachData(const py::dict& data, RunConfig* run,
                std::map<const PyObject*, std::shared_ptr<const Trajectory>>* tables) {
  for (const auto& [key, value] : data) {
    const std::string experiment = py::str(key);
    ExperimentSpec* spec = nullptr;
    for (ExperimentSpec& s : run->experiments) {
      if (s.name == experiment) spec = &s;
    }
    if (spec == nullptr) {
      throw PackageError(
          "data", "data given for '" + experiment + "', which is not an experiment of the config");
    }
    std::shared_ptr<const Trajectory>& table = (*tables)[value.ptr()];
    if (table == nullptr) table = TableFromColumns("experiment '" + experiment + "' (data given)", value);
    spec->table = table;
    Trajectory checked;
    CsvReadOptions options = spec->csv;
    options.columns.clear();
    std::string error;
    if (!TrajectoryFromTable(*spec->table, options, &checked, &error)) {
      throw PackageError("data", error);
    }
  }
}

// Whether a run's error is about its data: it names a record (a file or a given table).
bool AboutData(const RunConfig& config, const std::string& error) {
  for (const ExperimentSpec& spec : config.experiments) {
    if (!spec.file.empty() && error.find(spec.file) != std::string::npos) return true;
    if (spec.table && error.find(spec.table->source) != std::string::npos) return true;
  }
  return false;
}

ConfigFile Load(const ConfigArgument& config, const std::string& data_dir, const py::dict& data) {
  ConfigFile file;
  std::string error;
  if (!LoadConfig(config.Source(data_dir, data), Registry(), &file, &error)) {
    throw PackageError("config", error);
  }
  std::map<const PyObject*, std::shared_ptr<const Trajectory>> tables;
  AttachData(data, &file.run, &tables);
  return file;
}

// A config loaded without its records (every experiment may come as a frame).
ConfigFile LoadModelOnly(const ConfigArgument& config) {
  py::dict none;
  ConfigSource source = config.Source("", none);
  try {
    const YAML::Node root =
        config.is_text ? YAML::Load(config.config) : YAML::LoadFile(config.config);
    if (root["experiments"] && root["experiments"].IsSequence()) {
      for (const YAML::Node& e : root["experiments"]) {
        if (e.IsMap() && e["name"] && e["name"].IsScalar()) source.in_memory.insert(e["name"].Scalar());
      }
    }
  } catch (const YAML::Exception&) {
    // LoadConfig names the syntax error with its line.
  }
  source.read_reference = false;
  ConfigFile file;
  std::string error;
  if (!LoadConfig(source, Registry(), &file, &error)) throw PackageError("config", error);
  return file;
}

// Threads of every stage's solves and global start (0 keeps the config's): the results are
// the same on any number (thread_count_test.cc).
void SetThreads(int threads, RunConfig* run) {
  if (threads <= 0) return;
  for (StageConfig& stage : run->stages) {
    stage.options.local.num_threads = threads;
    stage.options.global.threads = threads;
  }
}

// Progress and Ctrl-C for a run made from Python. Python is called with the GIL held; a
// pending Ctrl-C (Python's handler runs the solves' callbacks on the main thread) ends the
// current solve after its iteration and the run after its stage (stop_request.h).
struct PythonWatch {
  py::object progress;
  bool interrupted = false;
  py::object raised;  // what the progress callback raised: raised again once the run stopped
  std::chrono::steady_clock::time_point last_poll{};

  // Interrupted(), at most every 50 ms: for the engine's polls (a global start's screening
  // asks at every point), each of which takes the GIL, which another Python thread may hold.
  bool PolledInterrupted() {
    const auto now = std::chrono::steady_clock::now();
    if (!interrupted && now - last_poll < std::chrono::milliseconds(50)) return false;
    last_poll = now;
    return Interrupted();
  }
  bool Interrupted() {
    if (!interrupted) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        PyErr_Clear();
        interrupted = true;
      }
    }
    if (interrupted) RequestStop();
    return interrupted;
  }
  void Tell(const py::dict& what) {
    if (Interrupted() || progress.is_none()) return;
    py::gil_scoped_acquire gil;
    try {
      progress(what);
    } catch (const py::error_already_set& e) {
      raised = e.value();  // a failing callback stops the run, as Ctrl-C does
      interrupted = true;
      RequestStop();
    }
  }
  // After the run: the callback's own exception, else KeyboardInterrupt when interrupted.
  void RaiseIfStopped(const char* what) {
    if (raised) {
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(raised.ptr())), raised.ptr());
      throw py::error_already_set();
    }
    if (interrupted) throw PackageError("interrupted", what);
  }
  RunObserver Observer() {
    RunObserver observer;
    observer.progress = [this](const SolveProgress& p) {
      py::gil_scoped_acquire gil;
      Tell(py::dict(py::arg("phase") = p.phase == SolveProgress::Phase::kGlobal ? "global" : "local",
                    py::arg("iteration") = p.iteration, py::arg("cost") = p.cost));
    };
    return observer;
  }
  RunRequest Request(const std::string& out_dir, bool write, bool report, bool config_is_file) {
    RunRequest request;
    request.write = write;
    request.out_dir = out_dir;
    request.html_report = report;
    request.config_is_file = config_is_file;
    request.checkpoint = false;  // no resume from Python: the records may be frames
    request.stop_requested = [this] { return Interrupted(); };
    return request;
  }
};

// The finished run as a RunResult; a run that did not finish raises.
std::shared_ptr<Run> Finished(const RunConfig& config, const RunOutcome& outcome) {
  switch (outcome.status) {
    case RunOutcome::Status::kInterrupted:
      throw PackageError("interrupted", "the run was interrupted");
    case RunOutcome::Status::kFailed:
      throw PackageError(AboutData(config, outcome.error) ? "data" : "run", outcome.error);
    case RunOutcome::Status::kStopped:
      throw PackageError("run", "the run stopped in stage '" + outcome.result.stopped_stage +
                                    "': " + outcome.error);
    default:
      break;
  }
  auto run = std::make_shared<Run>();
  run->config = std::make_shared<const RunConfig>(config);
  run->result = outcome.result;
  run->model = outcome.model;
  run->json = RunResultJsonText(config, run->result, -1);
  run->summary = RunResultToText(config, run->result);
  return run;
}

std::shared_ptr<Run> RunConfigured(const ConfigArgument& config, const std::string& data_dir,
                                   const py::dict& data, bool write, const std::string& out_dir,
                                   bool report, int threads, const py::object& progress) {
  ConfigFile file = Load(config, data_dir, data);
  SetThreads(threads, &file.run);
  PythonWatch watch{progress};
  RunOutcome outcome;
  ClearStopRequest();
  {
    const ScopedStopPoll poll([&watch] { return watch.PolledInterrupted(); });
    py::gil_scoped_release release;
    RunCommand(file.run, watch.Request(out_dir, write, report, !config.is_text), watch.Observer(),
               &outcome);
  }
  ClearStopRequest();
  watch.RaiseIfStopped("the run was interrupted");
  return Finished(file.run, outcome);
}

std::shared_ptr<Run> Select(const ConfigArgument& config, const std::string& data_dir,
                            const py::dict& data, bool write, const std::string& out_dir,
                            bool report, int threads, const py::object& progress) {
  SelectionSetup setup;
  std::string error;
  if (!LoadSelection(config.Source(data_dir, data), Registry(), &setup, &error)) {
    throw PackageError("config", error);
  }
  // The given records are every candidate's.
  std::map<const PyObject*, std::shared_ptr<const Trajectory>> tables;
  for (NamedCandidate& candidate : setup.candidates) {
    AttachData(data, &candidate.config, &tables);
    SetThreads(threads, &candidate.config);
  }
  if (threads > 0) setup.options.cases.threads = threads;
  PythonWatch watch{progress};
  auto line = [&watch](const std::string& text) {
    py::gil_scoped_acquire gil;
    watch.Tell(py::dict(py::arg("phase") = "select", py::arg("message") = text));
  };
  SelectOutcome outcome;
  bool selected = false;
  ClearStopRequest();
  {
    const ScopedStopPoll poll([&watch] { return watch.PolledInterrupted(); });
    py::gil_scoped_release release;
    selected = SelectCommand(setup, watch.Request(out_dir, write, report, !config.is_text),
                             watch.Observer(), line, nullptr, &outcome, &error);
  }
  ClearStopRequest();
  watch.RaiseIfStopped("the selection was interrupted");
  if (!selected) throw PackageError("run", error);
  return Finished(*outcome.chosen, outcome.run);
}

// `vesselid study`: (study.json's text, study.txt's).
std::pair<std::string, std::string> Study(const ConfigArgument& config,
                                          const std::string& data_dir, const py::dict& data,
                                          const std::vector<std::string>& only, bool write,
                                          const std::string& out_dir, int threads,
                                          const py::object& progress) {
  ConfigFile file = Load(config, data_dir, data);
  if (threads > 0) file.study.execution.threads = threads;
  auto line = [&](const std::string& message) {
    if (progress.is_none()) return;
    py::gil_scoped_acquire gil;
    try {
      progress(message);
    } catch (const py::error_already_set&) {
      // A failing callback does not stop the study.
    }
  };
  StudyOutcome outcome;
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = StudyCommand(file, only, write, out_dir, !config.is_text, line, &outcome, &error);
  }
  if (!ok) throw PackageError(AboutData(file.run, error) ? "data" : "run", error);
  return {outcome.result.dump(), outcome.text};
}

// `vesselid simulate`: the written files' names.
std::vector<std::string> Simulate(const ConfigArgument& config, const std::string& out_dir) {
  const ConfigFile file = LoadModelOnly(config);
  std::vector<std::string> files;
  std::string error;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = SimulateCommand(file, config.name, out_dir, !config.is_text, &files, &error);
  }
  if (!ok) throw PackageError(error.find(config.name) == 0 ? "config" : "run", error);
  return files;
}

// `vesselid export`: the written file's path; `runtime` the FMU runtime to pack (the
// package's copy).
std::string Export(const std::string& run_dir, const std::string& format,
                   const std::string& out_dir, int members, unsigned seed,
                   const std::string& runtime) {
  std::string error, path;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = ExportRun(Registry(), run_dir, format, out_dir, members, seed, runtime, &path, &error);
  }
  if (!ok) throw PackageError("run", error);
  return path;
}

// The model of a run in memory with `members` draws: what its results.json would give.
IdentifiedModel DrawnModel(const Run& run, int members, unsigned seed) {
  IdentifiedModel model;
  std::string error;
  if (members < 0) throw PackageError("run", "members must be >= 0");
  if (!IdentifiedModelOf(*run.config, run.result, members, seed, &model, &error)) {
    throw PackageError("run", error);
  }
  return model;
}

// `vesselid export` of a RunResult: no folder read.
std::string ExportResult(const Run& run, const std::string& format, const std::string& out_dir,
                         int members, unsigned seed, const std::string& runtime) {
  const IdentifiedModel model = DrawnModel(run, members, seed);
  std::string error, path;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = ExportModel(model, format, out_dir, runtime, &path, &error);
  }
  if (!ok) throw PackageError("run", error);
  return path;
}

// `vesselid predict` of a RunResult: (predictions.txt's text, predictions.json's).
std::pair<std::string, std::string> PredictResult(const Run& run, double length, double speed,
                                                  int members, unsigned seed, bool write,
                                                  const std::string& out_dir) {
  ManoeuvreConditions conditions;
  conditions.length = length;
  conditions.speed = speed;
  std::string error, text;
  if (!CheckPredictionArguments(conditions, members, &error)) throw PackageError("run", error);
  const IdentifiedModel model = DrawnModel(run, members, seed);
  const std::vector<ZigzagEntry> zigzags = ZigzagEntries(run.result.zigzags);
  nlohmann::json predictions;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = PredictModel(model, zigzags, conditions, write, out_dir, &predictions, &text, &error);
  }
  if (!ok) throw PackageError("run", error);
  return {text, predictions.dump()};
}

// `vesselid predict`: (predictions.txt's text, predictions.json's).
std::pair<std::string, std::string> Predict(const std::string& run_dir, double length,
                                            double speed, int members, unsigned seed, bool write,
                                            const std::string& out_dir) {
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
  if (!ok) throw PackageError("run", error);
  return {text, predictions.dump()};
}

// `vesselid design`: design.txt's text, design.json's, and the planned and predicted CSVs'.
std::tuple<std::string, std::string, std::string, std::string> Design(
    const ConfigArgument& config, const std::string& run_dir, bool write,
    const std::string& out_dir, int threads) {
  DesignResult result;
  std::string error;
  bool ok = false, config_error = false;
  {
    py::gil_scoped_release release;
    ok = DesignCommand(Registry(), config.is_text ? config.name : config.config,
                       config.is_text ? config.config : "", run_dir, threads, write, out_dir,
                       &result, &error, &config_error);
  }
  if (!ok) throw PackageError(config_error ? "config" : "run", error);
  return {DesignText(result), DesignToJson(result).dump(), PlannedInputCsv(result),
          PredictedCsv(result)};
}

}  // namespace

void BindCommands(py::module_& m) {
  py::class_<ConfigArgument>(m, "_Config")
      .def(py::init([](std::string config, bool is_text, std::string name) {
             return ConfigArgument{std::move(config), is_text, std::move(name)};
           }),
           py::arg("config"), py::arg("is_text"), py::arg("name"));
  m.def("run", &RunConfigured, py::arg("config"), py::arg("data_dir"), py::arg("data"),
        py::arg("write"), py::arg("out_dir"), py::arg("report"), py::arg("threads"),
        py::arg("progress"));
  m.def("select", &Select, py::arg("config"), py::arg("data_dir"), py::arg("data"),
        py::arg("write"), py::arg("out_dir"), py::arg("report"), py::arg("threads"),
        py::arg("progress"));
  m.def("study", &Study, py::arg("config"), py::arg("data_dir"), py::arg("data"),
        py::arg("only"), py::arg("write"), py::arg("out_dir"), py::arg("threads"),
        py::arg("progress"));
  m.def("simulate", &Simulate, py::arg("config"), py::arg("out_dir"));
  m.def("check_config", [](const ConfigArgument& config) { LoadModelOnly(config); },
        py::arg("config"));
  m.def("export_model", &Export, py::arg("run_dir"), py::arg("format"), py::arg("out_dir"),
        py::arg("members"), py::arg("seed"), py::arg("runtime"));
  m.def("export_result", &ExportResult, py::arg("run"), py::arg("format"), py::arg("out_dir"),
        py::arg("members"), py::arg("seed"), py::arg("runtime"));
  m.def("predict_result", &PredictResult, py::arg("run"), py::arg("length"), py::arg("speed"),
        py::arg("members"), py::arg("seed"), py::arg("write"), py::arg("out_dir"));
  m.def("predict", &Predict, py::arg("run_dir"), py::arg("length"), py::arg("speed"),
        py::arg("members"), py::arg("seed"), py::arg("write"), py::arg("out_dir"));
  m.def("design", &Design, py::arg("config"), py::arg("run_dir"), py::arg("write"),
        py::arg("out_dir"), py::arg("threads"));
}

}  // namespace vesselid::python
