#include "engine/run/work_size.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "engine/base/memory_budget.h"
#include "engine/model/experiment.h"
#include "engine/run/integration_step.h"

namespace vesselid {
namespace {

// Steps of one simulation over the samples of `t` in [begin, end] with steps no longer than
// `max_step` (0: the median interval, as BuildExperiment takes it): at least duration / step.
double StepsOver(const std::vector<double>& t, double begin, double end, double max_step,
                 double* step) {
  const auto first = std::lower_bound(t.begin(), t.end(), begin);
  const auto last = std::upper_bound(t.begin(), t.end(), end);
  if (last - first < 2) return 0.0;
  *step = max_step;
  if (*step <= 0.0) {
    std::vector<double> intervals;
    intervals.reserve(last - first - 1);
    for (auto k = first + 1; k != last; ++k) intervals.push_back(*k - *(k - 1));
    std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
    *step = intervals[intervals.size() / 2];
  }
  return (*(last - 1) - *first) / *step;
}

// Samples of `t` in [begin, end].
double SamplesIn(const std::vector<double>& t, double begin, double end) {
  return static_cast<double>(std::upper_bound(t.begin(), t.end(), end) -
                             std::lower_bound(t.begin(), t.end(), begin));
}

// What a run keeps per experiment (segment, piece) of a stage beyond its samples, measured
// on runs of 25 000 and 50 000 eight-sample segments (peak RSS, 11 KiB each with one output):
// its fit, findings, estimates of its initial states and the stage's checkpoint document of
// them, and per compared output its metrics and residual analysis.
constexpr double kPieceBytes = 6 * 1024.0;
constexpr double kPieceOutputBytes = 5 * 1024.0;

}  // namespace

bool CheckWorkSize(const RunConfig& config, TrajectoryCache* cache, std::string* error) {
  const double limit = static_cast<double>(config.limits.integration_steps);
  const double inputs = static_cast<double>(config.model->info().inputs.size());
  std::set<const Trajectory*> records;  // read once however many experiments share them
  double record_bytes = 0.0, trace_bytes = 0.0, piece_bytes = 0.0;
  for (size_t s = 0; s < config.stages.size(); ++s) {
    const StageConfig& stage = config.stages[s];
    std::vector<std::string> names = stage.experiments;
    names.insert(names.end(), stage.validation.begin(), stage.validation.end());
    double stage_steps = 0.0, stage_samples = 0.0, stage_pieces = 0.0;
    for (const std::string& name : names) {
      const ExperimentSpec* spec = config.FindExperiment(name);
      if (spec == nullptr) continue;  // the stage itself reports it
      const Trajectory* data = LoadCachedTrajectory(*spec, cache, error);
      if (data == nullptr) return false;
      if (records.insert(data).second) {
        record_bytes += sizeof(double) * static_cast<double>(data->t.size()) *
                        static_cast<double>(1 + data->columns.size());
      }
      // The pieces the record is identified as (segments, input ranges): gaps between them
      // are not integrated.
      std::vector<ExperimentSpec> pieces;
      if (!RecordSpecs(*spec, *data, 0.0, &pieces, error)) return false;
      piece_bytes += static_cast<double>(pieces.size()) *
                     (kPieceBytes + kPieceOutputBytes * static_cast<double>(spec->outputs.size()));
      stage_pieces += static_cast<double>(pieces.size());
      double step = 0.0, steps = 0.0;
      for (const ExperimentSpec& piece : pieces) {
        steps += StepsOver(data->t, piece.t_begin, piece.t_end,
                           IntegrationStep(StepUse::kStageFit, stage.experiment.max_step), &step);
        stage_samples += SamplesIn(data->t, piece.t_begin, piece.t_end) *
                         static_cast<double>(spec->outputs.size());
      }
      stage_steps += steps;
      if (!(steps > limit)) continue;
      char text[600];
      std::snprintf(text, sizeof(text),
                    "experiment '%s' (%s): stage '%s' integrates %.3g s of it in steps of at "
                    "most %.3g s (%s): %.3g integration steps, more than the limit of %.3g "
                    "(limits.integration_steps)",
                    name.c_str(), spec->file.c_str(), stage.options.name.c_str(), steps * step,
                    step,
                    stage.experiment.max_step > 0.0
                        ? ("stages[" + std::to_string(s) + "].integration.max_step").c_str()
                        : "the median sample interval; check the file's t column",
                    steps, limit);
      *error = text;
      return false;
    }
    // What the stage holds at once: every experiment's input cache and step times
    // (experiment.h) and samples (output, value, weight), beside the records read and the
    // traces and per-experiment results of this and the earlier stages (time, measured and
    // simulated per sample; kPieceBytes), which the run keeps for its report.
    const double cache_bytes = IntegrationStepBytes(stage_steps, inputs);
    const double sample_bytes = stage_samples * 3.0 * sizeof(double);
    trace_bytes += stage_samples * 3.0 * sizeof(double);
    const double total = record_bytes + cache_bytes + sample_bytes + trace_bytes + piece_bytes;
    if (total > static_cast<double>(MemoryBudget())) {
      char text[600];
      std::snprintf(text, sizeof(text),
                    " (the records read %s, input caches of %.3g integration steps %s, %.3g "
                    "samples %s, the traces kept for the report %s, the results of %.3g "
                    "experiments and segments %s); the step is "
                    "stages[%zu].integration.max_step, else the median sample interval",
                    FormatBytes(record_bytes).c_str(), stage_steps,
                    FormatBytes(cache_bytes).c_str(), stage_samples,
                    FormatBytes(sample_bytes).c_str(), FormatBytes(trace_bytes).c_str(),
                    stage_pieces, FormatBytes(piece_bytes).c_str(), s);
      *error = OverBudget("stage '" + stage.options.name + "': its experiments", total) + text;
      return false;
    }
  }
  return true;
}

}  // namespace vesselid
