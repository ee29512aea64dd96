// Everything doubtful about a finished run, as one list of lines for stderr, report.txt,
// report.html and results.json (RunResult::warnings), each naming its stage, parameter or
// experiment:
//   * the run stopped before its last stage;
//   * a stage worse on its held-out data than its start (set aside, or kept by final: last),
//     or worse on one held-out output though better over all;
//   * a held-out run whose simulation diverged;
//   * an estimate at a bound; a stage or final value that is not admissible;
//   * an integration step shortened, or still too long, for an estimate's dynamics;
//   * outlier experiments and initial states far from their guess (OutlierOptions);
//   * a solve that stopped at its iteration limit without converging;
//   * a failed fit: a channel with negative R^2, or an RMSE above kFailedFitNoiseRatio times
//     the noise level of its data (ChannelMetrics::noise);
//   * coloured residuals, or residuals correlated with past inputs (residual_warnings.h);
//   * final values whose held-out simulation diverges or predicts worse than holding the
//     first measured value.
#pragma once

#include <string>
#include <vector>

#include "engine/run/held_out.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Whether the final values' held-out simulation diverges or predicts an output worse than
// holding its first measured value; the reasons appended to `reasons` (may be null).
bool FinalHeldOutFailed(const RunResult& run, std::vector<std::string>* reasons);

// Appends the run's warnings to run->warnings.
void AddRunWarnings(const RunConfig& config, RunResult* run);

}  // namespace vesselid
