// What a stage says about its latent inputs (model/input_noise.h): per experiment and noisy
// input one note with the noise SD used, the spline's knot spacing and the corrections'
// spacing, RMS and range (not one line per value); and, when any experiment has a latent input,
// a narrow_intervals finding: the stage's standard errors hold the latent spline as
// exact, so they miss the part of the input noise the spline passes (measured: 1.5-2.3x too
// narrow on the cargo multi-sine, docs/configs.md "Noisy inputs"); a parametric bootstrap that adds the
// noise to the logged input and fits the spline again each run does not.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

// Appends the notes to `notes` and the finding to `findings`.
void InputNoiseNotes(const OutputErrorProblem& problem, std::vector<std::string>* notes,
                     std::vector<Finding>* findings);

}  // namespace vesselid
