#include "engine/run/continuation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace vesselid {
namespace {

std::string FormatSeconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g s", seconds);
  return text;
}

// Start values of the next phase: estimated parameters (within their bounds) and the initial
// states of segments that begin where a segment of the previous phase began.
void CarryForward(const OutputErrorProblem& solved, std::vector<ParameterSpec>* specs,
                  std::vector<StateAt>* states) {
  const std::vector<double> values = solved.ParametersOf(0);
  for (size_t i = 0; i < specs->size(); ++i) {
    ParameterSpec& spec = (*specs)[i];
    if (IsEstimatedOnce(spec.role)) spec.start = std::clamp(values[i], spec.lower, spec.upper);
  }
  states->clear();
  for (int e = 0; e < static_cast<int>(solved.experiments().size()); ++e) {
    const Experiment& experiment = solved.experiments()[e];
    states->push_back({experiment.record, experiment.node_time.front(), solved.InitialStateOf(e)});
  }
}

// The carried state of the segment that begins where `experiment` begins, or null.
const std::vector<double>* FindState(const std::vector<StateAt>& states,
                                     const Experiment& experiment) {
  constexpr double kTimeTolerance = 1e-6;
  for (const StateAt& s : states) {
    if (s.record == experiment.record &&
        std::abs(s.t0 - experiment.node_time.front()) < kTimeTolerance) {
      return &s.state;
    }
  }
  return nullptr;
}

}  // namespace

void SetCarriedStates(const std::vector<StateAt>& states, OutputErrorProblem* problem) {
  for (const Variable& v : problem->variables()) {
    if (v.kind != Variable::Kind::kInitialState || !v.free) continue;
    const std::vector<double>* state = FindState(states, problem->experiments()[v.experiment]);
    if (state != nullptr) v.set_value((*state)[v.index]);
  }
}

bool RunContinuation(const RunConfig& config, const StageConfig& stage, const ModelHandle& model,
                     TrajectoryCache* cache, const ProgressCallback& progress,
                     std::vector<ParameterSpec>* specs, std::vector<StateAt>* states,
                     std::vector<std::string>* notes, StageSummary* first_phase,
                     std::string* error) {
  for (size_t phase = 0; phase < stage.continuation.size(); ++phase) {
    const double length = stage.continuation[phase];
    std::vector<Experiment> experiments;
    if (!PrepareExperiments(config, stage.experiments, model, stage.experiment, cache,
                            &experiments, error, length)) {
      return false;
    }
    OutputErrorOptions phase_problem = stage.problem;
    for (const std::string& name : stage.continuation_free_states) {
      std::vector<std::string>& free = phase_problem.free_initial_states;
      if (std::find(free.begin(), free.end(), name) == free.end()) free.push_back(name);
    }
    std::unique_ptr<OutputErrorProblem> problem = OutputErrorProblem::Create(
        &model, std::move(experiments), *specs, phase_problem, error);
    if (problem == nullptr) return false;
    SetCarriedStates(*states, problem.get());
    StageOptions options = stage.options;
    options.use_global_start = options.use_global_start && phase == 0;
    options.compute_uncertainty = false;
    options.local.hold_bounds_at_end = false;  // the whole records' refinement does that
    if (phase > 0) options.local.initial_radius = kNearOptimumRadius;  // from the last phase
    if (progress) {
      options.local.progress = options.global.progress = [&progress, length](SolveProgress p) {
        p.segment_length = length;
        progress(p);
      };
    }
    StageSummary summary;
    if (!RunStage(options, problem.get(), &summary)) {
      *error = "continuation with " + FormatSeconds(length) + " segments: " + summary.message;
      return false;
    }
    const LocalSolveSummary& local = summary.local();
    char text[256];
    std::snprintf(text, sizeof(text),
                  "continuation: %s segments (%zu pieces), cost %.6e -> %.6e after %d "
                  "iterations, %.3f s",
                  FormatSeconds(length).c_str(), problem->experiments().size(), local.initial_cost,
                  local.final_cost, local.iterations, summary.time_seconds);
    notes->push_back(text);
    CarryForward(*problem, specs, states);
    if (phase == 0 && first_phase != nullptr) *first_phase = std::move(summary);
  }
  return true;
}

}  // namespace vesselid
