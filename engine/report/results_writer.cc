#include "engine/report/results_writer.h"

#include <filesystem>
#include <future>

#include "engine/base/atomic_file.h"
#include "engine/base/parallel_for.h"
#include "engine/base/stop_request.h"
#include "engine/data/trajectory.h"
#include "engine/output/checkpoint.h"
#include "engine/output/output_staging.h"
#include "engine/output/results_json_text.h"
#include "engine/output/results_text.h"
#include "engine/output/run_traces.h"
#include "engine/output/step_regression_writer.h"
#include "engine/report/report_html.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// One file per trace, formed and written in parallel, one at a time per thread (no copy of
// every trace at once); the first failure in the traces' order reported.
bool WriteTraces(const std::string& folder, const RunConfig& config, const RunResult& result,
                 std::string* error) {
  const std::vector<TraceSource> sources = RunTraceSources(config, result);
  std::vector<std::string> errors(sources.size());
  ParallelFor(static_cast<int>(sources.size()), 0, [&](int i) {
    if (StopRequested()) return;
    const NamedTrace trace = TraceOf(config, sources[i]);
    WriteTrajectoryCsv((fs::path(folder) / trace.file).string(), trace.trace, &errors[i]);
  });
  for (const std::string& e : errors) {
    if (e.empty()) continue;
    *error = e;
    return false;
  }
  return true;
}

}  // namespace

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error, bool html_report, bool with_checkpoint) {
  const std::unique_ptr<OutputStaging> staging =
      OutputStaging::Begin(out_dir, "run", error);
  if (staging == nullptr) return false;
  const std::string folder = staging->folder();
  std::error_code ec;
  const std::string traces = (fs::path(folder) / "traces").string();
  fs::create_directories(traces, ec);
  if (ec) {
    *error = traces + ": cannot create folder: " + ec.message();
    return false;
  }
  // report.html (its plots drawn by gnuplot processes) is formed while the traces and
  // report.txt are written; results.json waits for both.
  std::string html_error;
  std::future<bool> html;
  if (html_report) {
    html = std::async(std::launch::async,
                      [&]() { return WriteRunReport(config, result, folder, &html_error); });
  }
  const bool written = WriteTraces(traces, config, result, error) &&
                       WriteStepRegressionFiles(config, result, folder, error) &&
                       WriteFileAtomically((fs::path(folder) / "report.txt").string(),
                                           RunResultToText(config, result), error);
  if (html_report && !html.get() && written) {
    *error = html_error;
    return false;
  }
  const auto results_json = [&](std::ostream& out) {
    WriteRunResultJson(config, result, 2, &out);
    out << '\n';
  };
  if (!written || (with_checkpoint && !StageCheckpoint(out_dir, folder, error)) ||
      !WriteFileAtomically((fs::path(folder) / "results.json").string(), results_json, error)) {
    return false;
  }
  // A stop asked for while the files were formed (Ctrl-C) leaves the previous set.
  if (StopRequested()) {
    *error = "stopped before the results were published";
    return false;
  }
  return staging->Publish("results.json", error);
}

}  // namespace vesselid
