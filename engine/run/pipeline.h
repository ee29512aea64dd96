// A staged identification run (seed 002's hierarchy, generalised): stages run in order, each
// building its output-error problem from its experiments, its model restriction and its
// parameter roles. A parameter's start is its latest estimate unless the stage gives one;
// unlisted parameters are held there. After the last stage every parameter gets its final
// value: isolated and free ones from the last stage that estimated them, shared ones fused
// over all their stage estimates. Held-out experiments are simulated after each stage
// (local validation) and with the final values (final validation).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/parameter.h"
#include "engine/solve/progress.h"

namespace vesselid {

// What a run tells as it goes (terminal progress, checkpoints). Any member may be empty.
struct RunObserver {
  std::function<void(size_t index, const std::string& stage)> stage_started;
  // After each stage, before the next starts; false (with `error`) stops the run.
  std::function<bool(size_t index, const StageResult& stage, std::string* error)> stage_finished;
  ProgressCallback progress;  // solver iterations and global evaluations of output-error stages
};

// Runs every stage. On failure nothing is returned but the message naming the stage and cause.
// `finished` resumes a run: the results of its first stages, as an earlier run of the same
// config and data produced them (checkpoint.h); the run goes on from the next stage.
// `records` (optional) receives the records the run read, for the judgement (diagnose/).
bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const RunObserver& observer = {},
                       std::vector<StageResult> finished = {},
                       TrajectoryCache* records = nullptr);

// The parameter specs stage `index` is solved with after stages [0, index) ran as a run
// runs them (starts carried, unlisted parameters held at their latest estimates); `before`
// (optional) receives the results of those it needed (the stages up to the last one that
// estimates a parameter stage `index` carries) and `solved` (optional) the stage's own, run as
// the run runs it (continuation, global start). Used by studies of one stage.
bool ResolveStage(const RunConfig& config, size_t index, std::vector<ParameterSpec>* specs,
                  std::vector<StageResult>* before, std::string* error,
                  StageResult* solved = nullptr);

}  // namespace vesselid
