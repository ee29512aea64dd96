#include "engine/run/record_notes.h"

namespace vesselid {

void AddRecordNotes(const RunConfig& config, const TrajectoryCache& cache, RunResult* run) {
  std::vector<Finding> findings;
  for (const ExperimentSpec& spec : config.experiments) {
    const auto cached = cache.find(spec.name);
    if (cached == cache.end()) continue;
    const Trajectory& data = cached->second;
    findings.insert(findings.end(), data.findings.begin(), data.findings.end());
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
