#include "engine/output/run_traces.h"

#include "engine/base/file_name.h"
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

// `parts` joined by '.', as they are (the trace's name) or escaped (its file).
void AddSources(const std::vector<std::string>& parts, const std::vector<ExperimentFit>& fits,
                std::vector<TraceSource>* sources) {
  std::string name, file;
  for (const std::string& part : parts) {
    name += part + ".";
    file += FileNameOf(part) + ".";
  }
  for (const ExperimentFit& fit : fits) {
    sources->push_back({name + fit.experiment, file + FileNameOf(fit.experiment) + ".csv", &fit});
  }
}

}  // namespace

std::vector<TraceSource> RunTraceSources(const RunResult& result) {
  std::vector<TraceSource> sources;
  for (const StageResult& stage : result.stages) {
    AddSources({stage.name}, stage.summary.fits, &sources);
    AddSources({stage.name, "validation"}, stage.validation, &sources);
  }
  AddSources({"final_validation"}, result.final_validation, &sources);
  return sources;
}

NamedTrace TraceOf(const RunConfig& config, const TraceSource& source) {
  return {source.name, source.file, TraceInDisplayUnits(config, *source.fit)};
}

std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result) {
  std::vector<NamedTrace> traces;
  for (const TraceSource& source : RunTraceSources(result)) {
    traces.push_back(TraceOf(config, source));
  }
  return traces;
}

}  // namespace vesselid
