#include "engine/output/run_traces.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include "engine/base/file_name.h"
#include "engine/run/display_units.h"
#include "engine/run/records.h"

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

// The configured record `experiment` is a piece of ("" when it is one itself): a segment
// "<record>@<id>", a length piece "<record>@<k>" or an input range "<record>#<k>".
std::string RecordOfPiece(const std::set<std::string>& configured, const std::string& experiment) {
  if (configured.count(experiment) != 0) return "";
  const std::string record = RecordName(experiment);
  return record != experiment && configured.count(record) != 0 ? record : "";
}

// `parts` joined by '.', as they are (the trace's name) or escaped (its file); the pieces of
// a record gathered into one source, in the order of their first fit.
void AddSources(const std::set<std::string>& configured, const std::vector<std::string>& parts,
                const std::vector<ExperimentFit>& fits, std::vector<TraceSource>* sources) {
  std::string name, file;
  for (const std::string& part : parts) {
    name += part + ".";
    file += FileNameOf(part) + ".";
  }
  std::map<std::string, size_t> record_source;
  for (const ExperimentFit& fit : fits) {
    const std::string record = RecordOfPiece(configured, fit.experiment);
    if (record.empty()) {
      sources->push_back({name + fit.experiment, file + FileNameOf(fit.experiment) + ".csv",
                          {&fit}, false});
      continue;
    }
    const auto [found, added] = record_source.try_emplace(record, sources->size());
    if (added) {
      sources->push_back({name + record, file + FileNameOf(record) + ".csv", {}, true});
    }
    (*sources)[found->second].fits.push_back(&fit);
  }
}

// A piece's id: the number after its record's name and separator, else its place `k`.
double PieceId(const std::string& record, const std::string& experiment, size_t k) {
  const std::string id = experiment.substr(std::min(record.size() + 1, experiment.size()));
  char* end = nullptr;
  const double value = std::strtod(id.c_str(), &end);
  return !id.empty() && end == id.c_str() + id.size() ? value : static_cast<double>(k);
}

// The pieces' traces one after another, `segment` after t; a column a piece lacks is empty
// (NaN) in its rows.
Trajectory PiecesInDisplayUnits(const RunConfig& config, const std::vector<const ExperimentFit*>& fits) {
  const std::string record = RecordName(fits.front()->experiment);
  Trajectory joined;
  joined.names.push_back("segment");
  joined.columns.emplace_back();
  for (size_t k = 0; k < fits.size(); ++k) {
    const Trajectory trace = TraceInDisplayUnits(config, *fits[k]);
    const size_t before = joined.t.size();
    joined.t.insert(joined.t.end(), trace.t.begin(), trace.t.end());
    joined.columns[0].resize(joined.t.size(), PieceId(record, fits[k]->experiment, k));
    for (size_t c = 0; c < trace.names.size(); ++c) {
      int column = joined.Find(trace.names[c]);
      if (column < 0) {
        column = static_cast<int>(joined.names.size());
        joined.names.push_back(trace.names[c]);
        joined.columns.emplace_back(before, std::numeric_limits<double>::quiet_NaN());
      }
      std::vector<double>& values = joined.columns[column];
      values.insert(values.end(), trace.columns[c].begin(), trace.columns[c].end());
    }
    for (std::vector<double>& values : joined.columns) {
      values.resize(joined.t.size(), std::numeric_limits<double>::quiet_NaN());
    }
  }
  return joined;
}

}  // namespace

std::vector<TraceSource> RunTraceSources(const RunConfig& config, const RunResult& result) {
  std::set<std::string> configured;
  for (const ExperimentSpec& spec : config.experiments) configured.insert(spec.name);
  std::vector<TraceSource> sources;
  for (const StageResult& stage : result.stages) {
    AddSources(configured, {stage.name}, stage.summary.fits, &sources);
    AddSources(configured, {stage.name, "validation"}, stage.validation, &sources);
  }
  AddSources(configured, {"final_validation"}, result.final_validation, &sources);
  return sources;
}

NamedTrace TraceOf(const RunConfig& config, const TraceSource& source) {
  if (!source.pieces) {
    return {source.name, source.file, TraceInDisplayUnits(config, *source.fits.front())};
  }
  return {source.name, source.file, PiecesInDisplayUnits(config, source.fits)};
}

std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result) {
  std::vector<NamedTrace> traces;
  for (const TraceSource& source : RunTraceSources(config, result)) {
    traces.push_back(TraceOf(config, source));
  }
  return traces;
}

}  // namespace vesselid
