// White noise on a sampled input (a logged rudder), from the samples alone: its SD where
//   * the median |second difference| (robust to a zigzag's corners and steps; white noise of SD
//     sigma gives second differences of SD sqrt(6) sigma) puts sigma at 1e-3 or more of the
//     input's standard deviation, and
//   * the median |third difference| (SD sqrt(20) sigma) gives the same sigma within 0.8-1.25x,
//     where a signal smooth on the sampling scale leaves a factor (omega dt) less in each
//     higher difference;
// 0 otherwise. Samples equal to a neighbour (held: a zigzag's angle, a logger's exact zeros at
// rest, PWM levels, a quantised signal's steps) are left out of the differences; with fewer
// than 30 % of the samples (or 50 windows) left, the input is held or quantised: 0.
#pragma once

#include <vector>

namespace vesselid {

double WhiteInputNoise(const std::vector<double>& values);

}  // namespace vesselid
