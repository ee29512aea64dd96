// The standard manoeuvres among a run's simulated records: every stage's fit of its
// experiments and of its held-out runs, and the final validation. A record is examined when
// its experiment maps the model's rudder input (`delta`, or an input whose name starts with
// it) and the output `psi`:
//   zigzags (zigzag_figures.h): figures measured on the recorded heading and on the simulated
//     one (under the recorded rudder, the executes where the simulated heading reaches
//     +-psi_z), for the same t_0, psi_z and turn direction;
//   turning circles (turning_figures.h), where the model has a track (ModelInfo::TrackOutputs)
//     and the experiment maps both of its outputs: advance, transfer and tactical diameter of
//     the recorded track and of the simulated one, for the same rudder execute.
#pragma once

#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Fills run->zigzags and run->turning_circles.
void FindManoeuvreRuns(const RunConfig& config, RunResult* run, TrajectoryCache* cache);

}  // namespace vesselid
