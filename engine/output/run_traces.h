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
  // "final_validation.<experiment>".
  std::string name;
  // Its file in traces/: the same with each name escaped (FileNameOf, base/file_name.h),
  // ".csv" added; distinct for distinct names.
  std::string file;
  // t and per compared output "<output>_measured [unit]", "<output>_simulated [unit]", in
  // the unit the data came in (degrees where the experiment reads the column in degrees).
  Trajectory trace;
};

// Every trace of the run: each stage's experiments and held-out runs, then the final
// validation.
std::vector<NamedTrace> RunTraces(const RunConfig& config, const RunResult& result);

}  // namespace vesselid
