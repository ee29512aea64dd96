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
  // "final_validation.<experiment>"; traces/<name>.csv with '/' and ' ' made '_'.
  std::string name;
  // t and per compared output "<output>_measured [unit]", "<output>_simulated [unit]", in
  // the unit the data came in (degrees where the experiment reads the column in degrees).
  Trajectory trace;
};

// Every trace of the run: each stage's experiments and held-out runs, then the final
// validation.
std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result);

// The file name of a trace in traces/.
std::string TraceFileName(const std::string& name);

}  // namespace vesselid
