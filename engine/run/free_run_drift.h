// Noise is not structure, for the free run. Under gusts (the filter-error method's process
// noise) a correct ship model, flown alone from the record's start with the logged inputs,
// drifts from its record: the heading of a ship with white yaw-moment noise wanders as a
// random walk, and the free-run fit can fall below zero on a perfect model. Whether it has
// drifted further than the identified disturbance lets it is measured: the expected sum of
// squares of the free run's residuals of output j over experiment e is
//
//   E[SSE_j] = sum_i ( Var_w(y_j(t_i)) + R_j(t_i) ),
//
// Var_w the spread of the output at t_i over `kDriftMembers` free runs each in its own
// realisation of the identified process noise (Euler-Maruyama after every RK4 substep, the
// state moving by sqrt(q h) N(0, 1)), R_j the sensors' variance (the white, AR(1) and wave
// parts' variances, a bias's start variance plus q_b (t_i - t_0)). The ratio of the observed
// to the expected SSE is near 1 for a correct model (a random walk's 2 int W^2 has mean 1 and
// exceeds 8 with probability about 1 %: kDriftExplained, run_result.h), and far beyond where
// structure is missing. Only a
// filter-error stage with process noise is checked, and only where a free run is called failed
// or poor (output_error_stage.cc): the note stands beside those.
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_result.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

inline constexpr int kDriftMembers = 64;

// Per experiment and compared output of `problem` at its current values: the observed and
// expected free-run SSE (empty where the problem is not a filter-error one with process
// noise, or a simulation fails).
std::vector<FreeRunDrift> MeasureFreeRunDrift(const OutputErrorProblem& problem);

}  // namespace vesselid
