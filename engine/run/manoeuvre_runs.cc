#include "engine/run/manoeuvre_runs.h"

#include <map>

#include "engine/data/interpolation.h"
#include "engine/model/experiment.h"
#include "engine/model/record_channels.h"
#include "engine/run/zigzag_reflight.h"

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

struct Examiner {
  const RunConfig& config;
  TrajectoryCache* cache;
  RunResult* run;
  std::map<const Trajectory*, RecordChannels> channels;

  // A held-out zigzag flown from its measured start, re-flown in closed loop from the same
  // start with the same values (zigzag_reflight.h), the gear at the rate its log shows (IMO's
  // where it shows no ramp).
  void Refly(const ExperimentFit& fit, const ExperimentSpec& spec, const Trajectory& data,
             const std::vector<double>& delta, const std::vector<double>& psi,
             ZigzagRun* zigzag) {
    const ModelHandle& model = *config.model;
    const ModelInfo& info = model.info();
    if (fit.start.initial_state.size() != info.states.size() ||
        fit.start.values.size() != info.parameters.size()) {
      zigzag->reflown_why = "not flown from its measured start with the run's model";
      return;
    }
    if (RecordName(fit.experiment) != fit.experiment) {
      zigzag->reflown_why = "a piece of its record";
      return;
    }
    Experiment experiment;
    ZigzagCommands commands;
    ZigzagReflight flown;
    std::string why;
    if (!BuildExperiment(spec, data, info, ExperimentOptions(), &experiment, &why) ||
        !FindZigzagCommands(fit.trace.t, delta, psi, zigzag->test, &commands, &why) ||
        !ReflyZigzag(model, experiment, fit.start.values.data(), fit.start.initial_state.data(),
                     zigzag->test, commands,
                     std::isfinite(commands.rate) ? commands.rate : kImoRudderRate, &flown,
                     &why)) {
      zigzag->reflown_why = why;
      return;
    }
    zigzag->reflown_done = true;
    zigzag->reflown = flown.figures;
  }

  void Examine(const std::string& stage, bool held_out, const std::vector<ExperimentFit>& fits) {
    const ModelInfo& info = config.model->info();
    const auto [north, east] = info.TrackOutputs();
    for (const ExperimentFit& fit : fits) {
      if (fit.diverged) continue;
      const ExperimentSpec* spec = SpecOf(config, fit.experiment);
      if (spec == nullptr || spec->outputs.count("psi") == 0) continue;
      const std::string rudder = RudderColumn(*spec);
      const Trajectory& trace = fit.trace;
      const int measured = trace.Find("psi_measured"), simulated = trace.Find("psi_simulated");
      if (rudder.empty() || measured < 0 || simulated < 0) continue;
      std::string error;
      const Trajectory* data = LoadCachedTrajectory(*spec, cache, &error);
      if (data == nullptr || data->Find(rudder) < 0) continue;
      // The rudder column extracted once per record, not once per segment cut from it.
      const Channel& channel =
          channels.try_emplace(data, *data).first->second.Extracted(data->Find(rudder));
      const std::vector<double> delta = InterpolateAt(channel, Interpolation::kLinear, trace.t);
      ZigzagRun zigzag;
      if (DetectZigzag(trace.t, delta, trace.columns[measured], &zigzag.test)) {
        zigzag.stage = stage;
        zigzag.experiment = fit.experiment;
        zigzag.held_out = held_out;
        zigzag.measured = MeasureZigzag(trace.t, trace.columns[measured], zigzag.test);
        zigzag.simulated = MeasureZigzag(trace.t, trace.columns[simulated], zigzag.test);
        if (held_out) Refly(fit, *spec, *data, delta, trace.columns[measured], &zigzag);
        run->zigzags.push_back(std::move(zigzag));
        continue;
      }
      if (north < 0) continue;
      const std::string x = info.outputs[north], y = info.outputs[east];
      const int xm = trace.Find(x + "_measured"), xs = trace.Find(x + "_simulated");
      const int ym = trace.Find(y + "_measured"), ys = trace.Find(y + "_simulated");
      TurningRun turning;
      if (xm < 0 || xs < 0 || ym < 0 || ys < 0 ||
          !DetectTurningCircle(trace.t, delta, trace.columns[measured], &turning.test)) {
        continue;
      }
      turning.stage = stage;
      turning.experiment = fit.experiment;
      turning.held_out = held_out;
      turning.unit = info.OutputUnit(north);
      turning.measured = MeasureTurningCircle(trace.t, trace.columns[xm], trace.columns[ym],
                                              trace.columns[measured], turning.test);
      turning.simulated = MeasureTurningCircle(trace.t, trace.columns[xs], trace.columns[ys],
                                               trace.columns[simulated], turning.test);
      run->turning_circles.push_back(std::move(turning));
    }
  }
};

}  // namespace

void FindManoeuvreRuns(const RunConfig& config, RunResult* run, TrajectoryCache* cache) {
  run->zigzags.clear();
  run->turning_circles.clear();
  Examiner examiner{config, cache, run, {}};
  for (const StageResult& stage : run->stages) {
    examiner.Examine(stage.name, false, stage.summary.fits);
    examiner.Examine(stage.name, true, stage.validation);
  }
  examiner.Examine("final", true, run->final_validation);
}

}  // namespace vesselid
