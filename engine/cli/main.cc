// vesselid: identify vessel motion models from recorded trajectories.
//
//   vesselid simulate <config.yaml> --out <dir>                 synthetic experiments
//   vesselid run      <config.yaml> [--data <dir>] --out <dir>  staged identification
//                     [--resume] [--quiet | --verbose] [--no-report] [--strict]
//   vesselid findings                                           the catalogue of finding kinds
//   vesselid study    <config.yaml> [--data <dir>] --out <dir>  sensitivity studies (the
//                     [--only part...] [--threads n]             config's `study` section;
//                                                                also under mpirun -np K)
//   vesselid export   <run-out> [--format fmu|c|json] [--out <dir>]  the model taken out
//                     [--members n] [--seed s]
//   vesselid predict  <run-out> [--length L] [--speed U]     IMO zigzags and turning, with
//                     [--out <dir>] [--members n]             intervals
//   vesselid design   <config.yaml> --from <run-out>          the next experiment, planned
//                     [--out <dir>] [--threads n] [--quiet]    from the fit (config's design:)
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "CLI/CLI.hpp"
#include "engine/base/parallel_for.h"
#include "engine/base/stop_request.h"
#include "engine/base/version.h"
#include "engine/cli/terminal_progress.h"
#include "engine/command/design_command.h"
#include "engine/command/run_command.h"
#include "engine/command/select_command.h"
#include "engine/command/simulate_command.h"
#include "engine/command/study_command.h"
#include "engine/config/config.h"
#include "engine/design/design_report.h"
#include "engine/diagnose/run_findings.h"
#include "engine/export/export_run.h"
#include "engine/export/fmu_package.h"
#include "engine/output/checkpoint.h"
#include "engine/output/finding_report.h"
#include "engine/output/reserved_names.h"
#include "engine/output/results_text.h"
#include "engine/output/selection_report.h"
#include "engine/select/selection_config.h"
#include "engine/study/study_runner.h"
#include "glog/logging.h"
#include "problems/registry.h"

namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "vesselid: error: %s\n", message.c_str());
  return 1;
}

// Every model family the program knows; outlives every config (a config points at its family).
const vesselid::ModelRegistry& Registry() {
  static const vesselid::ModelRegistry registry = vesselid::DefaultRegistry();
  return registry;
}

bool Load(const std::string& config_path, const std::string& data_dir,
          vesselid::ConfigFile* config, std::string* error, bool read_reference = true) {
  return vesselid::LoadConfigFile(config_path, data_dir, Registry(), config, error,
                                  read_reference);
}

int Simulate(const std::string& config_path, const std::string& out_dir) {
  vesselid::ConfigFile config;
  std::string error;
  std::vector<std::string> files;
  // The records are made before any run: a reference run need not exist yet.
  if (!Load(config_path, out_dir, &config, &error, /*read_reference=*/false) ||
      !vesselid::SimulateCommand(config, config_path, out_dir, true, &files, &error)) {
    return Fail(error);
  }
  std::printf("simulated experiments of %s into %s\n", config_path.c_str(), out_dir.c_str());
  return 0;
}

// The model of the run in `run_dir` taken out as `format` (json: model.json; fmu: an FMI 2.0
// co-simulation FMU; c: C99 header, source and example) into `out_dir` (default
// <run_dir>/export), published as one set.
int Export(const std::string& run_dir, const std::string& format, const std::string& out_dir,
           int members, unsigned seed) {
  std::string error, runtime, path;
  if (format == "fmu" && (runtime = vesselid::FindFmuRuntime(&error)).empty()) return Fail(error);
  if (!vesselid::ExportRun(Registry(), run_dir, format, out_dir, members, seed, runtime, &path,
                           &error)) {
    return Fail(error);
  }
  std::printf("model of %s written to %s\n", run_dir.c_str(), path.c_str());
  return 0;
}

// The standard manoeuvres the model of the run in `run_dir` predicts, with intervals, into
// `out_dir` (default <run_dir>/predict): predictions.txt and predictions.json, one set.
int Predict(const std::string& run_dir, const std::string& out_dir,
            const vesselid::ManoeuvreConditions& conditions, int members, unsigned seed) {
  std::string error, text;
  nlohmann::json predictions;
  // Each member flies six manoeuvres (about 3 ms each on one core): say so before a long wait.
  if (members >= 5000) {
    std::fprintf(stderr, "vesselid: flying the manoeuvres with %d ensemble members (%d per core)\n",
                 members, members / std::max(1, vesselid::ParallelThreads(0)));
  }
  if (!vesselid::PredictRun(Registry(), run_dir, conditions, members, seed, true, out_dir,
                            &predictions, &text, &error)) {
    return Fail(error);
  }
  std::printf("%s", text.c_str());
  return 0;
}

// The next experiment planned from the run in `run_dir` as the config's design section asks,
// written into `out_dir` (default <run_dir>/design) as one set; design.txt printed.
int Design(const std::string& config_path, const std::string& run_dir, const std::string& out_dir,
           int threads, bool quiet) {
  vesselid::DesignResult result;
  std::string error;
  if (!vesselid::DesignCommand(Registry(), config_path, "", run_dir, threads, true, out_dir,
                               &result, &error)) {
    return Fail(error);
  }
  const std::string where =
      out_dir.empty() ? (std::filesystem::path(run_dir) / "design").string() : out_dir;
  if (quiet) {
    std::printf("%s\n", where.c_str());
  } else {
    std::printf("%s\nwritten to %s\n", vesselid::DesignText(result).c_str(), where.c_str());
  }
  return result.limit_violations.empty() ? 0 : 1;
}

// SIGINT (Ctrl-C), SIGTERM or SIGHUP (the terminal closed) during a run: the solves end after their current iteration
// (stop_request.h), the stage cut short is not saved and no output is published; the run
// says where it stopped and how to go on. A second signal ends the process at once (the
// checkpoint still holds every finished stage).
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void OnStopSignal(int signal) {
  stop_signal = signal;
  vesselid::RequestStop();  // a lock-free atomic store: safe in a handler
  static const char kLine[] =
      "\nvesselid: stopping after the current solver iteration (again to end at once)\n";
  const ssize_t ignored = ::write(STDERR_FILENO, kLine, sizeof(kLine) - 1);
  (void)ignored;
}

void CatchStopSignals() {
  struct sigaction action = {};
  action.sa_handler = OnStopSignal;
  action.sa_flags = SA_RESETHAND;  // the second signal takes its default action
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);
}

struct RunFlags {
  bool quiet = false;
  bool verbose = false;
  bool resume = false;
  bool no_report = false;  // batch use: results.json, report.txt and traces, no report.html
  bool strict = false;     // exit 3 on a doubtful verdict, 4 on a failed one
};

// Exit codes of a finished run under --strict (0 otherwise, whatever the verdict).
constexpr int kExitDoubtful = 3;
constexpr int kExitFailed = 4;

// The line a run stopped by a signal ends with: where it stopped, what the checkpoint holds and
// the command that goes on from there; exit status 128 + the signal, as the shell's.
int Interrupted(const std::string& config_path, const std::string& data_dir,
                const std::string& out_dir, const vesselid::RunConfig& config, size_t stage) {
  const int signal = stop_signal;
  const std::string name = signal == SIGINT    ? "SIGINT"
                           : signal == SIGTERM ? "SIGTERM"
                           : signal == SIGHUP  ? "SIGHUP"
                                               : "a signal";
  const std::string again = "vesselid run " + config_path +
                            (data_dir.empty() ? "" : " --data " + data_dir) + " --out " + out_dir;
  const std::string resume = again + " --resume";
  const size_t total = config.stages.size();
  std::string where;
  if (stage < total) {
    where = "in stage '" + config.stages[stage].options.name + "' (" + std::to_string(stage + 1) +
            " of " + std::to_string(total) + "); " +
            // Resume is advised only where it goes on from this run's own checkpoint.
            (stage == 0 ? "no stage finished: `" + again + "` starts it again"
                        : std::to_string(stage) + " finished stage(s) are in its checkpoint (" +
                              out_dir + "/" + vesselid::kWorkingCheckpoint + "): `" + resume +
                              "` goes on from stage '" +
                              config.stages[stage].options.name + "'");
  } else {
    where = "before its results were published; its stages are in its checkpoint (" + out_dir +
            "/" + vesselid::kWorkingCheckpoint + "): `" + resume +
            "` writes them without solving again";
  }
  std::fprintf(stderr, "vesselid: interrupted by %s %s (no results published: %s is as before)\n",
               name.c_str(), where.c_str(), out_dir.c_str());
  return 128 + signal;
}

// What a finished run prints: the summary (unless quiet), its failures and warnings on stderr
// (notes too with --verbose), the results path and the verdict last; the exit status.
int Finished(const vesselid::RunConfig& config, const std::string& out_dir,
             const RunFlags& flags, const vesselid::RunOutcome& outcome) {
  const vesselid::RunResult& result = outcome.result;
  if (!flags.quiet) std::cout << vesselid::RunResultToText(config, result);
  const std::vector<vesselid::Finding> findings = vesselid::AllFindings(result);
  for (const vesselid::Finding& f : findings) {
    if (f.severity == vesselid::FindingSeverity::kInfo && !flags.verbose) continue;
    std::fprintf(stderr, "vesselid: %s\n", vesselid::DescribeFinding(f).c_str());
  }
  std::printf("%sresults written to %s\n", flags.quiet ? "" : "\n",
              (std::filesystem::path(out_dir) / "results.json").lexically_normal().c_str());
  if (outcome.status == vesselid::RunOutcome::Status::kStopped) {
    return Fail("the run stopped in stage '" + result.stopped_stage + "': " + outcome.error +
                "; the " + std::to_string(result.stages.size()) + " finished stage(s) are in " +
                out_dir + "/results.json");
  }
  std::fprintf(stderr, "vesselid: %s\n", vesselid::VerdictLine(result.verdict, findings).c_str());
  if (flags.strict && result.verdict == vesselid::Verdict::kDoubtful) return kExitDoubtful;
  if (flags.strict && result.verdict == vesselid::Verdict::kFailed) return kExitFailed;
  return 0;
}

// How a run ended, for the shell: its outputs and verdict, or why it did not finish.
int Ended(const vesselid::RunConfig& config, const std::string& config_path,
          const std::string& data_dir, const std::string& out_dir, const RunFlags& flags,
          const vesselid::RunOutcome& outcome) {
  switch (outcome.status) {
    case vesselid::RunOutcome::Status::kInterrupted:
      return Interrupted(config_path, data_dir, out_dir, config, outcome.stage);
    case vesselid::RunOutcome::Status::kFailed:
      return Fail(outcome.error);
    default:
      return Finished(config, out_dir, flags, outcome);
  }
}

// The request of a run from the command line: a checkpoint in out_dir after each stage; with
// --resume, the stages an earlier run of the same config and data finished are loaded, not
// rerun; a signal stops it after the current solver iteration.
vesselid::RunRequest Request(const std::string& out_dir, const RunFlags& flags,
                             vesselid::TerminalProgress* progress) {
  vesselid::RunRequest request;
  request.out_dir = out_dir;
  request.resume = flags.resume;
  request.html_report = !flags.no_report;
  request.stop_requested = [] { return stop_signal != 0; };
  request.note = [progress](const std::string& line) { progress->Note(line); };
  return request;
}

// The observer that shows a run's progress on stderr.
vesselid::RunObserver Observer(vesselid::TerminalProgress* progress) {
  vesselid::RunObserver observer;
  observer.stage_started = [progress](size_t index, const std::string& name) {
    progress->StageStarted(index, name);
  };
  observer.progress = [progress](const vesselid::SolveProgress& p) { progress->Iteration(p); };
  observer.stage_finished = [progress](size_t, const vesselid::StageResult& stage, std::string*) {
    progress->StageFinished(stage);
    return true;
  };
  return observer;
}

// A staged run (run_command.h): progress on stderr, the outputs and verdict at the end.
int RunConfigured(const vesselid::RunConfig& config, const std::string& config_path,
                  const std::string& data_dir, const std::string& out_dir, const RunFlags& flags) {
  vesselid::TerminalProgress progress(
      vesselid::TerminalProgress::ChooseMode(stderr, flags.quiet, flags.verbose), stderr,
      config.stages.size());
  vesselid::RunOutcome outcome;
  CatchStopSignals();
  vesselid::RunCommand(config, Request(out_dir, flags, &progress), Observer(&progress), &outcome);
  return Ended(config, config_path, data_dir, out_dir, flags, outcome);
}

int Run(const std::string& config_path, const std::string& data_dir, const std::string& out_dir,
        const RunFlags& flags) {
  vesselid::ConfigFile file;
  std::string error;
  if (!Load(config_path, data_dir, &file, &error)) return Fail(error);
  return RunConfigured(file.run, config_path, data_dir, out_dir, flags);
}

// The config's `select` section: every candidate cross-validated over the runs (a case per
// candidate and fold, over threads and MPI ranks), then the chosen candidate run on every
// run as `vesselid run` runs a config, its outputs showing the selection.
int Select(const std::string& config_path, const std::string& data_dir, const std::string& out_dir,
           int threads, const RunFlags& flags) {
  const vesselid::ProcessGroup group(nullptr, nullptr);  // MPI under mpirun
  vesselid::SelectionSetup setup;
  std::string error;
  if (!vesselid::LoadSelection(config_path, data_dir, Registry(), &setup, &error)) {
    return group.root() ? Fail(error) : 1;
  }
  if (threads > 0) setup.options.cases.threads = threads;
  const bool report = !flags.quiet && group.root();
  auto lines = [report](const std::string& line) {
    if (report) std::fprintf(stderr, "%s\n", line.c_str());
  };
  // The chosen candidate's stages are shown as a run's.
  vesselid::TerminalProgress progress(
      vesselid::TerminalProgress::ChooseMode(stderr, flags.quiet, flags.verbose), stderr, 0);
  vesselid::SelectOutcome outcome;
  CatchStopSignals();
  auto chosen = [&](const vesselid::SelectOutcome& selection) {
    if (!flags.quiet) std::cout << vesselid::SelectionText(*selection.selection) << "\n";
    progress.set_stages(selection.chosen->stages.size());
  };
  const bool selected =
      vesselid::SelectCommand(setup, Request(out_dir, flags, &progress), Observer(&progress),
                              lines, chosen, &outcome, &error);
  if (!outcome.root) return selected ? 0 : 1;
  if (!selected) return Fail(error);
  return Ended(*outcome.chosen, config_path, data_dir, out_dir, flags, outcome.run);
}

// The config's `study` section on the config's data. Under `mpirun` every rank runs its share
// of each part's cases and rank 0 alone writes study.txt and study.json, and only when every
// part ran.
int Study(const std::string& config_path, const std::string& data_dir, const std::string& out_dir,
          const std::vector<std::string>& only, int threads, bool quiet) {
  const vesselid::ProcessGroup group(nullptr, nullptr);  // MPI under mpirun
  vesselid::ConfigFile config;
  std::string error;
  if (!Load(config_path, data_dir, &config, &error)) {
    return group.root() ? Fail(error) : 1;
  }
  if (threads > 0) config.study.execution.threads = threads;
  const bool report = !quiet && group.root();
  auto progress = [report](const std::string& line) {
    if (report) std::fprintf(stderr, "%s\n", line.c_str());
  };
  vesselid::StudyOutcome outcome;
  const bool ok = vesselid::StudyCommand(config, only, true, out_dir, true, progress, &outcome, &error);
  if (!outcome.root) return ok ? 0 : 1;
  if (!ok) return Fail(error);
  if (!quiet) std::cout << outcome.text;
  // What a part found doubtful reaches stderr too, as a run's findings do.
  for (const auto& [part, section] : outcome.result.items()) {
    if (!section.is_object() || !section.contains("notes")) continue;
    for (const auto& note : section["notes"]) {
      std::fprintf(stderr, "note: study %s: %s\n", part.c_str(),
                   note.get<std::string>().c_str());
    }
  }
  std::printf("\nstudy written to %s/study.json\n", out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Ceres reports through glog; vesselid reports solver outcomes itself.
  google::InitGoogleLogging(argv[0]);
  // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported as a write error
  // (temporary files removed), instead of killing the process mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
  FLAGS_minloglevel = google::GLOG_FATAL;
  CLI::App app{"vesselid: output-error identification of vessel motion models"};
  app.set_version_flag("--version", vesselid::kVersion);
  app.require_subcommand(1);
  std::string config_path, out_dir, data_dir;
  bool quiet = false;

  CLI::App* simulate = app.add_subcommand("simulate", "write a config's synthetic experiments");
  simulate->add_option("config", config_path, "run configuration (YAML)")->required();
  simulate->add_option("--out", out_dir, "folder for the CSV files")->required();

  CLI::App* export_model = app.add_subcommand(
      "export", "take a run's model out: an FMI 2.0 FMU, C99 code or model.json");
  std::string run_dir, format = "fmu";
  int members = 100;
  unsigned seed = 1;
  export_model->add_option("run", run_dir, "the --out folder of a finished run")->required();
  export_model
      ->add_option("--format", format,
                   "fmu (FMI 2.0 co-simulation), c (C99 header, source, example) or json")
      ->check(CLI::IsMember({"json", "fmu", "c"}));
  export_model->add_option("--out", out_dir, "folder for the export (default <run>/export)");
  export_model->add_option("--members", members,
                           "parameter draws from the covariance (ensemble_member 1..N)");
  export_model->add_option("--seed", seed, "seed of the draws");

  CLI::App* predict = app.add_subcommand(
      "predict", "the standard manoeuvres (IMO zigzags, initial turning) a run's model predicts");
  vesselid::ManoeuvreConditions conditions;
  predict->add_option("run", run_dir, "the --out folder of a finished run")->required();
  predict->add_option("--length", conditions.length, "ship length L (m)");
  predict->add_option("--speed", conditions.speed, "approach speed U (m/s)");
  predict->add_option("--out", out_dir, "folder for the predictions (default <run>/predict)");
  predict->add_option("--members", members, "parameter draws for the ensemble intervals");
  predict->add_option("--seed", seed, "seed of the draws");

  CLI::App* run = app.add_subcommand("run", "staged identification");
  run->add_option("config", config_path, "run configuration (YAML)")->required();
  run->add_option("--data", data_dir,
                  "folder the experiment files are relative to "
                  "(default: the config's folder)");
  run->add_option("--out", out_dir,
                  "folder for results.json, report.txt, report.html, traces/, checkpoint/")
      ->required();
  RunFlags run_flags;
  CLI::Option* quiet_flag = run->add_flag("--quiet", run_flags.quiet, "print only the results path");
  run->add_flag("--verbose", run_flags.verbose,
                "a line per iteration and every stage note (default: a live status line on a "
                "terminal, a line per stage otherwise)")
      ->excludes(quiet_flag);
  run->add_flag("--resume", run_flags.resume,
                "continue from the last stage the checkpoint in --out finished");
  run->add_flag("--no-report", run_flags.no_report,
                "batch use: write results.json, report.txt and traces/ but no report.html "
                "(an earlier one in --out is removed)");

  run->add_flag("--strict", run_flags.strict,
                "batch and CI use: exit 3 when the verdict is doubtful and 4 when it is failed "
                "(every output is written either way)");

  CLI::App* findings = app.add_subcommand(
      "findings", "print the catalogue of finding kinds: rule, severity, what to do (Markdown)");

  CLI::App* study = app.add_subcommand(
      "study", "sensitivity studies: profile likelihood, Monte Carlo, start points, partitions");
  study->add_option("config", config_path, "run configuration (YAML) with a study section")
      ->required();
  study->add_option("--data", data_dir,
                    "folder the experiment files are relative to "
                    "(default: the config's folder)");
  study->add_option("--out", out_dir, "folder for study.txt and study.json")->required();
  study->add_flag("--quiet", quiet, "print only the results path");
  std::vector<std::string> only;
  int threads = 0;
  study->add_option("--only", only, "run only these parts (profile, monte_carlo, starts, partitions)");
  study->add_option("--threads", threads, "worker threads per process (default: study.threads, "
                    "else cores / processes)");

  CLI::App* select = app.add_subcommand(
      "select",
      "structure selection: the config's candidates cross-validated over its runs, "
      "then the chosen one run");
  select->add_option("config", config_path, "run configuration (YAML) with a select section")
      ->required();
  select->add_option("--data", data_dir,
                     "folder the experiment files are relative to "
                     "(default: the config's folder)");
  select
      ->add_option("--out", out_dir,
                   "folder for the chosen candidate's results.json, report.txt, report.html")
      ->required();
  RunFlags select_flags;
  select->add_flag("--quiet", select_flags.quiet, "print only the results path");
  select->add_flag("--no-report", select_flags.no_report, "no report.html");
  int select_threads = 0;
  select->add_option("--threads", select_threads,
                     "worker threads per process (default: select.threads, else cores)");

  CLI::App* design = app.add_subcommand(
      "design", "plan the next experiment from a run's fit (the config's design section)");
  design->add_option("config", config_path, "configuration (YAML) with a design section")
      ->required();
  design->add_option("--from", run_dir, "the --out folder of the finished run")->required();
  design->add_option("--out", out_dir, "folder for the plan (default <run>/design)");
  int design_threads = 0;
  design->add_option("--threads", design_threads,
                     "worker threads (default: design.search.threads, "
                     "else cores)");
  bool design_quiet = false;
  design->add_flag("--quiet", design_quiet, "print only the plan's folder");

  CLI11_PARSE(app, argc, argv);
  if (design->parsed()) return Design(config_path, run_dir, out_dir, design_threads, design_quiet);
  if (simulate->parsed()) return Simulate(config_path, out_dir);
  if (export_model->parsed()) return Export(run_dir, format, out_dir, members, seed);
  if (predict->parsed()) {
    // NaN stands for "not given" inside: a NaN given is refused as the number it is not.
    for (const auto& [flag, value] : {std::pair{"--length", conditions.length},
                                      std::pair{"--speed", conditions.speed}}) {
      if (predict->count(flag) > 0 && std::isnan(value)) return Fail(std::string(flag) + " nan: not a number");
    }
    return Predict(run_dir, out_dir, conditions, members, seed);
  }
  if (findings->parsed()) {
    std::cout << vesselid::FindingCatalogueMarkdown();
    return 0;
  }
  if (study->parsed()) return Study(config_path, data_dir, out_dir, only, threads, quiet);
  if (select->parsed()) {
    return Select(config_path, data_dir, out_dir, select_threads, select_flags);
  }
  return Run(config_path, data_dir, out_dir, run_flags);
}
