// What a stage says about its latent inputs (model/input_noise.h): per experiment and noisy
// input one note with the noise SD used, the spline's knot spacing and the corrections'
// spacing, RMS and range (not one line per value).
#pragma once

#include <string>
#include <vector>

#include "engine/solve/output_error_problem.h"

namespace vesselid {

std::vector<std::string> InputNoiseNotes(const OutputErrorProblem& problem);

}  // namespace vesselid
