// The RK4 step of every simulation a run makes, decided here and nowhere else. The value is
// ExperimentOptions::max_step (0: each record's median sample interval, BuildExperiment):
//
//   kStageFit            the stage's `integration.max_step`, else 0. A stage whose estimate's
//                        dynamics outrun that step is re-refined at a shorter one
//                        (step_stability.h); that step is StageResult::integration_step.
//   kStageValidation     the step the stage ended with: held-out runs and the stage's start
//                        are simulated as its fit was.
//   kFinalValidation     the shortest step any accepted stage ended with (the final values
//                        carry the fastest dynamics a stage needed), else the final
//                        validation's own `integration.max_step`.
//   kVelocityValidation  a tenth of the record's grid interval: the grid may be slow (GNSS)
//                        next to fast internal dynamics (a propeller lag), and an RK4 step
//                        beyond ~2.8 time constants is unstable; the stages' step where that
//                        is shorter.
#pragma once

#include <vector>

#include "engine/run/run_result.h"

namespace vesselid {

enum class StepUse { kStageFit, kStageValidation, kFinalValidation, kVelocityValidation };

// `configured`: the stage's (or the final validation's) `integration.max_step` (0: none);
// `stages`: the stage whose fit is validated, or the accepted stages for the final values;
// `grid_interval`: the velocity record's grid interval (kVelocityValidation only).
double IntegrationStep(StepUse use, double configured,
                       const std::vector<const StageResult*>& stages = {},
                       double grid_interval = 0.0);

}  // namespace vesselid
