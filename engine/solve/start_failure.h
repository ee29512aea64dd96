// Why an output-error problem cannot be evaluated at its current values (its start values),
// for the message of a stage that cannot begin: the first experiment whose simulation fails,
// the outputs that become non-finite and when, the inputs over the step that breaks,
// non-finite initial states, and the physical conditions of the model
// (ModelHandle::Admissibility) the values break ("M is not positive definite ... m - Xudot =
// 11 - 20 <= 0"); or, when every simulation runs, the first residual or derivative that is
// not finite, named by experiment, output, time and variable.
#pragma once

#include <string>

#include "engine/solve/output_error_problem.h"

namespace vesselid {

// "" when the residuals and their derivatives are finite. (Non-const: Ceres evaluates.)
std::string StartFailure(OutputErrorProblem* problem);

}  // namespace vesselid
