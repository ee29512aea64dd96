#include "engine/run/record_notes.h"

namespace vesselid {

void AddRecordNotes(const RunConfig& config, const TrajectoryCache& cache, RunResult* run) {
  std::vector<std::string> names;
  for (const ExperimentSpec& spec : config.experiments) names.push_back(spec.name);
  const std::vector<Finding> findings = cache.Findings(names);
  for (const ExperimentSpec& spec : config.experiments) {
    const Trajectory* cached = cache.Find(spec.name);
    if (cached == nullptr) continue;
    const Trajectory& data = *cached;
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
  run->findings.insert(run->findings.begin(), findings.begin(), findings.end());
}

}  // namespace vesselid
