// White noise on a sampled input (a logged rudder), from the samples alone: its SD where
//   * the median |second difference| (robust to a zigzag's corners and steps; white noise of SD
//     sigma gives second differences of SD sqrt(6) sigma) puts sigma at 1e-3 or more of the
//     input's standard deviation, and
//   * the median |third difference| (SD sqrt(20) sigma) gives the same sigma within 0.8-1.25x,
//     where a signal smooth on the sampling scale leaves a factor (omega dt) less in each
//     higher difference;
// 0 otherwise, and for held or quantised inputs (PWM steps, a clean zigzag held constant:
// more than 20 % of consecutive samples equal).
#pragma once

#include <vector>

namespace vesselid {

double WhiteInputNoise(const std::vector<double>& values);

}  // namespace vesselid
