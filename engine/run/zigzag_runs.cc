#include "engine/run/zigzag_runs.h"

#include <map>

#include "engine/data/interpolation.h"
#include "engine/model/record_channels.h"

namespace vesselid {
namespace {

// The configured experiment a fit belongs to (a segment "<name>@<k>" or piece "<name>#<k>").
const ExperimentSpec* SpecOf(const RunConfig& config, const std::string& experiment) {
  return config.FindExperiment(RecordName(experiment));
}

// The record's rudder column: the one mapped to the input `delta` (or delta...).
std::string RudderColumn(const ExperimentSpec& spec) {
  for (const auto& [input, column] : spec.inputs) {
    if (input == "delta") return column;
  }
  for (const auto& [input, column] : spec.inputs) {
    if (input.rfind("delta", 0) == 0) return column;
  }
  return "";
}

void Examine(const RunConfig& config, const std::string& stage, bool held_out,
             const std::vector<ExperimentFit>& fits, TrajectoryCache* cache,
             std::map<const Trajectory*, RecordChannels>* channels,
             std::vector<ZigzagRun>* runs) {
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) continue;
    const ExperimentSpec* spec = SpecOf(config, fit.experiment);
    if (spec == nullptr || spec->outputs.count("psi") == 0) continue;
    const std::string rudder = RudderColumn(*spec);
    const int measured = fit.trace.Find("psi_measured"),
              simulated = fit.trace.Find("psi_simulated");
    if (rudder.empty() || measured < 0 || simulated < 0) continue;
    std::string error;
    const Trajectory* data = LoadCachedTrajectory(*spec, cache, &error);
    if (data == nullptr || data->Find(rudder) < 0) continue;
    // The rudder column extracted once per record, not once per segment cut from it.
    const Channel& channel =
        channels->try_emplace(data, *data).first->second.Extracted(data->Find(rudder));
    const std::vector<double> delta = InterpolateAt(channel, Interpolation::kLinear, fit.trace.t);
    ZigzagRun run;
    if (!DetectZigzag(fit.trace.t, delta, fit.trace.columns[measured], &run.test)) continue;
    run.stage = stage;
    run.experiment = fit.experiment;
    run.held_out = held_out;
    run.measured = MeasureZigzag(fit.trace.t, fit.trace.columns[measured], run.test);
    run.simulated = MeasureZigzag(fit.trace.t, fit.trace.columns[simulated], run.test);
    runs->push_back(std::move(run));
  }
}

}  // namespace

std::vector<ZigzagRun> FindZigzagRuns(const RunConfig& config, const RunResult& run,
                                      TrajectoryCache* cache) {
  std::vector<ZigzagRun> runs;
  std::map<const Trajectory*, RecordChannels> channels;
  for (const StageResult& stage : run.stages) {
    Examine(config, stage.name, false, stage.summary.fits, cache, &channels, &runs);
    Examine(config, stage.name, true, stage.validation, cache, &channels, &runs);
  }
  Examine(config, "final", true, run.final_validation, cache, &channels, &runs);
  return runs;
}

}  // namespace vesselid
