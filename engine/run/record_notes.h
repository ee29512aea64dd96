// What preparing the recorded data did, brought into the run's result: every record's
// preparation notes (epoch origin, samples the screen removed, resampling, segments skipped
// as too short; experiment_data.h, records.h) first among the run's findings, and where its
// times and positions start (RunResult::record_origins).
#pragma once

#include "engine/run/records.h"
#include "engine/run/run_result.h"

namespace vesselid {

// In config order, for every record `cache` holds.
void AddRecordNotes(const RunConfig& config, const TrajectoryCache& cache, RunResult* run);

}  // namespace vesselid
