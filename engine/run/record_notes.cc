#include "engine/run/record_notes.h"

namespace vesselid {

void AddRecordNotes(const RunConfig& config, const TrajectoryCache& cache, RunResult* run) {
  std::vector<std::string> notes;
  for (const ExperimentSpec& spec : config.experiments) {
    const auto cached = cache.find(spec.name);
    if (cached == cache.end()) continue;
    const Trajectory& data = cached->second;
    notes.insert(notes.end(), data.notes.begin(), data.notes.end());
    if (!data.epoch && !data.position_origin) continue;
    RecordOrigin origin;
    origin.experiment = spec.name;
    origin.epoch = data.epoch;
    origin.time_origin_ns = data.time_origin_ns;
    origin.position = data.position_origin;
    origin.lat = data.origin_lat;
    origin.lon = data.origin_lon;
    run->record_origins.push_back(origin);
  }
  run->warnings.insert(run->warnings.begin(), notes.begin(), notes.end());
}

}  // namespace vesselid
