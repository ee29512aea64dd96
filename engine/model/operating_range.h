// The range a stage's records take the model to, over which physical conditions on functions
// of the state and input are judged (ModelHandle::Admissibility): damping that must not feed
// the motion up to the speeds reached, a thrust law monotone over the commands given. A flat
// vector (archived with the stage) laid out as
//   [ max |x_0|, ..., max |x_{nx-1}|,  min u_0, max u_0, ..., min u_{nu-1}, max u_{nu-1} ]
// with the states from a simulation at the estimate and the inputs from the records (an input
// with no sample: +inf, -inf).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/model/experiment.h"

namespace vesselid {

// An empty range for nx states and nu inputs (states 0, inputs [+inf, -inf]).
inline std::vector<double> EmptyOperatingRange(int nx, int nu) {
  std::vector<double> range(nx, 0.0);
  for (int i = 0; i < nu; ++i) {
    range.push_back(std::numeric_limits<double>::infinity());
    range.push_back(-std::numeric_limits<double>::infinity());
  }
  return range;
}

// Widens the input part of `range` (after nx states) by the inputs the experiment's
// simulation reads (its input cache).
inline void AddInputRange(const Experiment& e, int nx, std::vector<double>* range) {
  const int nu = e.num_inputs;
  for (size_t row = 0; row * nu < e.input_cache.size(); ++row) {
    for (int i = 0; i < nu; ++i) {
      const double u = e.input_cache[row * nu + i];
      if (std::isnan(u)) continue;
      double& low = (*range)[nx + 2 * i];
      double& high = (*range)[nx + 2 * i + 1];
      low = std::min(low, u);
      high = std::max(high, u);
    }
  }
}

// Widens `range` by `other` of the same layout (nx states first).
inline void MergeOperatingRange(const std::vector<double>& other, int nx,
                                std::vector<double>* range) {
  for (size_t i = 0; i < range->size() && i < other.size(); ++i) {
    const bool low = static_cast<int>(i) >= nx && (i - nx) % 2 == 0;
    (*range)[i] = low ? std::min((*range)[i], other[i]) : std::max((*range)[i], other[i]);
  }
}

}  // namespace vesselid
