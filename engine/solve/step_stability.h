// Whether the integration step can follow the model's dynamics at an estimate. RK4 is stable
// for h |lambda| up to about 2.8 on the real axis and accurate well below it; a fit that drives
// a time constant towards the step fits the integrator instead of the vessel (its estimate
// moves with the step). Along each experiment's simulation the state Jacobian df/dx is
// formed by central differences every few steps and its eigenvalue of largest modulus
// gives h |lambda| for that step.
#pragma once

#include <string>

#include "engine/solve/output_error_problem.h"

namespace vesselid {

// Largest h |lambda| accepted without a smaller step, and the one a smaller step aims at.
inline constexpr double kStepStabilityLimit = 1.0;
inline constexpr double kStepStabilityTarget = 0.5;

struct StepStability {
  double worst = 0.0;         // largest h |lambda| met
  double fastest_rate = 0.0;  // its |lambda|, 1/s
  double step = 0.0;          // its h, s
  double time = 0.0;          // where, s
  std::string experiment;

  // The step that brings the worst h |lambda| to kStepStabilityTarget.
  double SafeStep() const { return kStepStabilityTarget / fastest_rate; }
  // "h |lambda| = 2.9 (time constant 0.0069 s, step 0.02 s) at t = 12 s in 'validation@2'".
  std::string Describe() const;
};

// Checks every experiment of the problem at its current values.
StepStability CheckStepStability(const OutputErrorProblem& problem);

}  // namespace vesselid
