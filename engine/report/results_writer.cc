#include "engine/report/results_writer.h"

#include <filesystem>
#include <future>

#include "engine/base/atomic_file.h"
#include "engine/base/parallel_for.h"
#include "engine/data/trajectory.h"
#include "engine/report/report_html.h"
#include "engine/output/results_json_text.h"
#include "engine/output/results_text.h"
#include "engine/output/run_traces.h"
#include "engine/output/step_regression_writer.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// One file per trace, written in parallel; the first failure in the traces' order reported.
bool WriteTraces(const std::string& folder, const std::vector<NamedTrace>& traces,
                 std::string* error) {
  std::vector<std::string> errors(traces.size());
  ParallelFor(static_cast<int>(traces.size()), 0, [&](int i) {
    const std::string path = (fs::path(folder) / traces[i].file).string();
    WriteTrajectoryCsv(path, traces[i].trace, &errors[i]);
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
                     std::string* error, bool html_report) {
  std::error_code ec;
  const std::string traces = (fs::path(out_dir) / "traces").string();
  fs::create_directories(traces, ec);
  if (ec) {
    *error = out_dir + ": cannot create folder: " + ec.message();
    return false;
  }
  // report.html (its plots drawn by gnuplot processes) is formed while the traces and
  // report.txt are written; results.json waits for both.
  std::string html_error;
  std::future<bool> html;
  if (html_report) {
    html = std::async(std::launch::async, [&]() {
      return WriteRunReport(config, result, out_dir, &html_error);
    });
  }
  const bool written =
            WriteTraces(traces, RunTraces(config, result), error) &&
            WriteStepRegressionFiles(config, result, out_dir, error) &&
            WriteFileAtomically((fs::path(out_dir) / "report.txt").string(),
                                RunResultToText(config, result), error);
  if (html_report && !html.get() && written) {
    *error = html_error;
    return false;
  }
  if (!written) return false;
  if (!html_report) {
    const fs::path stale = fs::path(out_dir) / "report.html";
    fs::remove(stale, ec);
    if (ec) {
      *error = stale.string() + ": cannot remove the earlier run's report: " + ec.message();
      return false;
    }
  }
  return WriteFileAtomically((fs::path(out_dir) / "results.json").string(),
                             RunResultJsonText(config, result) + "\n", error);
}

}  // namespace vesselid
