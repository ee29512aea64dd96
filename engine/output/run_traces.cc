#include "engine/output/run_traces.h"

#include "engine/run/display_units.h"

namespace vesselid {
namespace {

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

void AddTraces(const RunConfig& config, const std::string& prefix,
               const std::vector<ExperimentFit>& fits, std::vector<NamedTrace>* traces) {
  for (const ExperimentFit& fit : fits) {
    traces->push_back({prefix + "." + fit.experiment, TraceInDisplayUnits(config, fit)});
  }
}

}  // namespace

std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result) {
  std::vector<NamedTrace> traces;
  for (const StageResult& stage : result.stages) {
    AddTraces(config, stage.name, stage.summary.fits, &traces);
    AddTraces(config, stage.name + ".validation", stage.validation, &traces);
  }
  AddTraces(config, "final_validation", result.final_validation, &traces);
  return traces;
}

std::string TraceFileName(const std::string& name) {
  std::string file = name + ".csv";
  for (char& c : file) {
    if (c == '/' || c == ' ') c = '_';
  }
  return file;
}

}  // namespace vesselid
