// Continuation phases of a stage (`continuation: [5, 10]`): the stage's problem solved with
// every training record cut into shorter segments, shortest first, each phase starting from
// the previous one's solution. A start far from the optimum cannot wrap a heading or lose a
// circling vessel's phase over a few seconds, so the short horizons lead the long one into
// its basin. The first phase takes the stage's global start; none reports uncertainty.
#pragma once

#include <string>
#include <vector>

#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

// An estimated initial state, keyed by record and start time, handed between phases.
struct StateAt {
  std::string record;
  double t0;
  std::vector<double> state;
};

// Runs the stage's continuation phases (none if it has none). `specs` leave with the last
// phase's estimates as starts (within their bounds), `states` with its segments' initial
// states; `notes` get one line per phase, `first_phase` (may be null) the first phase's
// summary (its global start's). `progress` (may be empty) hears every phase's solves.
bool RunContinuation(const RunConfig& config, const StageConfig& stage, const ModelHandle& model,
                     TrajectoryCache* cache, const ProgressCallback& progress,
                     std::vector<ParameterSpec>* specs, std::vector<StateAt>* states,
                     std::vector<std::string>* notes, StageSummary* first_phase,
                     std::string* error);

// Free initial states of the problem's experiments take the carried values of segments that
// begin where one of `states` began.
void SetCarriedStates(const std::vector<StateAt>& states, OutputErrorProblem* problem);

}  // namespace vesselid
