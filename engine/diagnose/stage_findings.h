// A stage's judgement: its solver's own findings (StageSummary::findings) and those derived
// from what the stage reports, computed from the reported values so that none is stale
// after a re-solve:
//   at_bound       a free estimate (or a held-out run's own value) within 1e-6 of its range
//                  from a bound, as reported;
//   no_convergence the chosen solve stopped at its iteration limit;
//   no_progress    the chosen solve made no successful step (a warning when the fit failed
//                  or the solver did not converge there, else info: the start was an optimum);
//   failed_fit     per output, the experiments whose simulation missed the record (FitFailed);
//   poor_fit       per output, those it explains less than half of (FitPoor);
//   residuals, compensation, bootstrap, admissibility, held-out checks (their own headers).
#pragma once

#include <vector>

#include "engine/base/finding.h"
#include "engine/model/model.h"
#include "engine/run/display_units.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Sets stage->findings and stage->verdict; `output_error`: the stage was solved by Ceres
// (a regression stage's "solve" is its regression: no solver findings).
// Values of outputs in messages are in `unit_of`'s units (the data's: degrees where the column
// was read in degrees); without it in the model's.
// Parameter values likewise in `parameter_unit_of`'s (a rudder bias in degrees where the
// rudder column was).
void DiagnoseStage(const ModelInfo& info, bool output_error, StageResult* stage,
                   const DisplayUnitOf& unit_of = {},
                   const ParameterUnitOf& parameter_unit_of = {});

// at_bound findings of `estimates` (free or per-experiment parameters with finite bounds),
// named for `stage` ("final" for the final validation's held-out runs); values and bounds in
// `unit_of`'s unit (may be empty: the model's).
void AddBoundFindings(const ModelInfo& info, const std::vector<Estimate>& estimates,
                      const std::string& stage, std::vector<Finding>* findings,
                      const ParameterUnitOf& unit_of = {});

// failed_fit and poor_fit findings of `fits`, one per kind and output with the count of
// experiments; the worst run's MAE in `unit_of`'s unit (may be empty: the model's). Where a
// failed or poor free run drifts no further than the identified process noise lets a correct
// model (`drift`, free_run_drift.h) and `findings` holds no disturbance_absorbs_structure for
// its output, a free_run_drift note says so beside it (the fit's finding stands).
void AddFitFindings(const std::vector<ExperimentFit>& fits, const std::string& stage,
                    std::vector<Finding>* findings, const DisplayUnitOf& unit_of = {},
                    const std::vector<FreeRunDrift>& drift = {});

// held_out_free_run_failed findings of velocity-validation `metrics` (free-run R2 < 0), one per
// held-out record set and state, with `severity` (warning for a stage, failure for the final
// values).
void AddFreeRunFindings(const std::vector<ChannelMetrics>& metrics, const std::string& stage,
                        FindingSeverity severity, std::vector<Finding>* findings);

}  // namespace vesselid
