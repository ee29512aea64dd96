#include "engine/report/results_writer.h"

#include <filesystem>
#include <future>

#include "engine/base/atomic_file.h"
#include "engine/base/parallel_for.h"
#include "engine/data/trajectory.h"
#include "engine/run/display_units.h"
#include "engine/report/report_html.h"
#include "engine/output/results_json.h"
#include "engine/output/results_text.h"
#include "engine/output/step_regression_writer.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

std::string TraceFileName(const std::string& prefix, const std::string& experiment) {
  std::string name = prefix + "." + experiment + ".csv";
  for (char& c : name) {
    if (c == '/' || c == ' ') c = '_';
  }
  return name;
}

// The trace in the units the user reads (display_units.h), each column's unit in its header:
// "psi_measured [deg]".
Trajectory TraceInDisplayUnits(const RunConfig& config, const ExperimentFit& fit) {
  Trajectory trace = fit.trace;
  for (size_t c = 0; c < trace.names.size(); ++c) {
    const std::string& name = trace.names[c];
    const size_t cut = name.rfind('_');
    const DisplayUnit unit = OutputDisplayUnit(config, fit.experiment, name.substr(0, cut));
    for (double& v : trace.columns[c]) v *= unit.scale;
    trace.names[c] = WithUnit(name, unit.unit);
  }
  return trace;
}

// One file per experiment, written in parallel; the first failure in the fits' order reported.
bool WriteTraces(const RunConfig& config, const std::string& folder, const std::string& prefix,
                 const std::vector<ExperimentFit>& fits, std::string* error) {
  std::vector<std::string> errors(fits.size());
  ParallelFor(static_cast<int>(fits.size()), 0, [&](int i) {
    const std::string path =
        (fs::path(folder) / TraceFileName(prefix, fits[i].experiment)).string();
    WriteTrajectoryCsv(path, TraceInDisplayUnits(config, fits[i]), &errors[i]);
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
  bool written = true;
  for (const StageResult& stage : result.stages) {
    if (!written) break;
    written = WriteTraces(config, traces, stage.name, stage.summary.fits, error) &&
              WriteTraces(config, traces, stage.name + ".validation", stage.validation, error);
  }
  written = written &&
            WriteTraces(config, traces, "final_validation", result.final_validation, error) &&
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
                             RunResultToJson(config, result).dump(2) + "\n", error);
}

}  // namespace vesselid
