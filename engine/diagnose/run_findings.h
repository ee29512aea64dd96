// The judgement of a finished run (the diagnose layer's entry point): every stage's findings
// and verdict (stage_findings.h), and the run's own findings:
//   run_stopped            the run stopped before its last stage;
//   stage_set_aside        repeated at run level: the final values do not use that stage;
//   not_admissible         the final values break a physical condition (a failure);
//   final_held_out_failed  the final values' held-out simulation diverges or predicts an
//                          output worse than holding its first measured value;
//   at_bound               a final held-out run's own value on its bound;
// with what the pipeline found about the records (RunResult::findings as it left them).
// Findings are folded (one per kind, stage, parameter and output, with a count) and sorted
// severity first.
//
// The verdict rule: a stage's verdict is that of its findings (failed on a failure, doubtful
// on a warning, else good). The run's is the worse of its own findings' and the last kept
// stage's (the stage whose estimates make the final values; earlier stages are starts, so
// their doubts are shown but do not judge the result).
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/held_out.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Sets every stage's findings and verdict, and the run's; with the run's `records` (may be
// null) also what the records say: units, record checks, noise on inputs.
void DiagnoseRun(const RunConfig& config, RunResult* run, TrajectoryCache* records = nullptr);

// RunIdentification (pipeline.h), then DiagnoseRun on whatever it returned (also when the run
// stopped in a stage); the same return value and error.
bool Identify(const RunConfig& config, RunResult* result, std::string* error,
              const RunObserver& observer = {}, std::vector<StageResult> finished = {});

// Merges findings that differ only in their experiment (and message) into one with the sum
// of their counts and the first's message followed by " (also in zz2, zz3)"; record findings
// (removed samples, grids, origins, cuts) and different segments are not merged.
std::vector<Finding> FoldFindings(const std::vector<Finding>& findings);

}  // namespace vesselid
