#include "engine/output/results_writer.h"

#include <filesystem>

#include "engine/base/atomic_file.h"
#include "engine/data/trajectory.h"
#include "engine/output/display_units.h"
#include "engine/output/report_html.h"
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

bool WriteTraces(const RunConfig& config, const std::string& folder, const std::string& prefix,
                 const std::vector<ExperimentFit>& fits, std::string* error) {
  for (const ExperimentFit& fit : fits) {
    const std::string path = (fs::path(folder) / TraceFileName(prefix, fit.experiment)).string();
    if (!WriteTrajectoryCsv(path, TraceInDisplayUnits(config, fit), error)) return false;
  }
  return true;
}

}  // namespace

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error) {
  std::error_code ec;
  const std::string traces = (fs::path(out_dir) / "traces").string();
  fs::create_directories(traces, ec);
  if (ec) {
    *error = out_dir + ": cannot create folder: " + ec.message();
    return false;
  }
  for (const StageResult& stage : result.stages) {
    if (!WriteTraces(config, traces, stage.name, stage.summary.fits, error) ||
        !WriteTraces(config, traces, stage.name + ".validation", stage.validation, error)) {
      return false;
    }
  }
  if (!WriteTraces(config, traces, "final_validation", result.final_validation, error) ||
      !WriteStepRegressionFiles(config, result, out_dir, error) ||
      !WriteFileAtomically((fs::path(out_dir) / "report.txt").string(),
                           RunResultToText(config, result), error) ||
      !WriteRunReport(config, result, out_dir, error)) {
    return false;
  }
  return WriteFileAtomically((fs::path(out_dir) / "results.json").string(),
                             RunResultToJson(config, result).dump(2) + "\n", error);
}

}  // namespace vesselid
