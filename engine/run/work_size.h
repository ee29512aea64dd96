// The work a run's config implies, checked before its first stage: the integration steps of
// every record each stage simulates, its validation runs included, summed over the pieces the
// record is identified as (segments, input ranges), against limits.integration_steps, and
// what the stage then holds (records, input caches, samples) against limits.memory_mb. A step
// bound typed a few orders too small, or a time column with one absurd value, is refused with
// the number and the key that caused it instead of exhausting memory hours into the run.
#pragma once

#include <string>

#include "engine/run/records.h"
#include "engine/run/run_config.h"

namespace vesselid {

// Loads the data of every experiment a stage uses into `cache` (reading errors are returned
// as they are) and checks the steps each stage's integration implies.
bool CheckWorkSize(const RunConfig& config, TrajectoryCache* cache, std::string* error);

}  // namespace vesselid
