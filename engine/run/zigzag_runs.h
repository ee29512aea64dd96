// The zigzags among a run's simulated records (zigzag_figures.h): every stage's fit of its
// experiments and of its held-out runs, and the final validation. A record is examined when
// its experiment maps the model's rudder input (`delta`, or an input whose name starts with
// it) and the output `psi`; its figures are measured on the recorded heading and on the
// simulated one (under the recorded rudder, the executes where the simulated heading reaches
// +-psi_z), for the same t_0, psi_z and turn direction.
#pragma once

#include <vector>

#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

std::vector<ZigzagRun> FindZigzagRuns(const RunConfig& config, const RunResult& run,
                                      TrajectoryCache* cache);

}  // namespace vesselid
