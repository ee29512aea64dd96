// An experiment's residuals at a solved problem's current values, per sample and in the
// outputs' model units: simulated minus measured (r_i / w_i, wrapped as the residual is).
#pragma once

#include <vector>

#include "engine/solve/output_error_problem.h"

namespace vesselid {

// d_i of experiment e's samples; NaN where a sample has no weight. False when its simulation
// cannot be evaluated.
bool SimulatedMinusMeasured(OutputErrorProblem* problem, int e, std::vector<double>* d);

}  // namespace vesselid
