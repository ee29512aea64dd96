// The measured-against-simulated traces of a run, as `vesselid run` writes them into traces/
// and the Python package returns them (Result.traces).
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

struct NamedTrace {
  // "<stage>.<experiment>", "<stage>.validation.<experiment>" (held-out runs) or
  // "final_validation.<experiment>". The segments or pieces of one record (its `segments`
  // column, `segment_length`, input ranges) share one trace named for the record, its pieces
  // one after another with a `segment` column after t: a log cut into 500 000 segments gives
  // one file, not 500 000.
  std::string name;
  // Its file in traces/: the same with each name escaped (FileNameOf, base/file_name.h),
  // ".csv" added; distinct for distinct names.
  std::string file;
  // t (with pieces, `segment`: the piece's id, the value of the record's segment column or
  // k of its k-th length piece or input range) and per compared output
  // "<output>_measured [unit]", "<output>_simulated [unit]", in the unit the data came in
  // (degrees where the experiment reads the column in degrees).
  Trajectory trace;
};

// A trace named but not yet formed: its fit in `result`, or the fits of a record's pieces.
struct TraceSource {
  std::string name, file;  // as NamedTrace's
  std::vector<const ExperimentFit*> fits;
  bool pieces = false;  // the fits are pieces of the record `name` ends with
};

// Every trace of the run, in order: each stage's experiments and held-out runs, then the
// final validation. Formed one at a time (TraceOf), a run's traces are written without a
// second copy of them all in memory.
std::vector<TraceSource> RunTraceSources(const RunConfig& config, const RunResult& result);
NamedTrace TraceOf(const RunConfig& config, const TraceSource& source);

// Every trace of the run, formed (the Python package's Result.traces).
std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result);

}  // namespace vesselid
