// Savitzky-Golay smoothing and differentiation of a uniformly sampled signal: a polynomial of
// degree `order` is fitted by least squares to the 2 m + 1 samples around each sample and
// evaluated (or differentiated) there. Near the ends the window is shifted to lie inside the
// record and the fit is evaluated off-centre, so the output has the input's length without
// padding. Exact for polynomials up to `order`. Angles must be unwrapped by the caller.
//
// Used to derive body velocities and yaw rate from positions and heading (equation-error
// regression data), never for output-error residuals, which stay on the raw measurements.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

struct SavitzkyGolayOptions {
  int half_width = 5;  // m: the window holds 2 m + 1 samples
  int order = 2;       // polynomial degree, < 2 m + 1
  int derivative = 0;  // 0: smoothed values, 1: first derivative, ... (<= order)
};

// `y` sampled every `dt` seconds. False with a message if the options do not fit the data.
bool SavitzkyGolay(const std::vector<double>& y, double dt, const SavitzkyGolayOptions& options,
                   std::vector<double>* out, std::string* error);

}  // namespace vesselid
