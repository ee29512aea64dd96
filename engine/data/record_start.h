// The rate of a measured channel at the start of a record, for start values of
// initial states (a body velocity or a yaw rate is rarely measured, but follows from the
// measured positions and angles).
//
// A quadratic y(t) = a + b (t - t0) + c (t - t0)^2 is fitted by least squares to the samples in
// [t0, t0 + window] (at least the first three samples); the rate is b. Angle channels are
// unwrapped over the window first.
#pragma once

#include "engine/data/trajectory.h"

namespace vesselid {

// The fit's value and rate at t0 with their standard errors from its residual
// (s^2 = SSR / (m - 3), covariance s^2 (X'X)^-1); the errors are NaN with only three samples.
struct StartFit {
  double value = 0.0, rate = 0.0;
  double value_sigma = 0.0, rate_sigma = 0.0;
};

// False (fit untouched) if the channel has fewer than three samples at or after t0.
bool FitStart(const Channel& channel, double t0, double window, bool angle, StartFit* fit);

// The rate alone (FitStart).
bool RateAt(const Channel& channel, double t0, double window, bool angle, double* rate);

}  // namespace vesselid
