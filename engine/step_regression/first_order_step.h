// Inertia from one step response (seed 004, Eriksen & Breivik, §3.3 "Extraction of inertia
// data"): around the i-th input step the response is approximated by the local first-order
// linear model (seed eq. 6)
//
//   m dy' + k dy = du,   dy = y - y_before,   du = input change,
//   k = du / (y_after - y_before)            (linearised damping, from the two steady states)
//
// whose step response from rest at t_step is
//
//   y(t) = y_before + (y_after - y_before) (1 - exp(-(t - t_step) / T)),   T = m / k.
//
// k is fixed by the steady states, so the only unknown is the inertia m, or equivalently T. The
// seed simulates (6) for a set of candidate inertias and keeps the one with the smallest squared
// error; here T is searched on a log grid over [min_time_constant, max_time_constant] and the
// best grid point is refined by golden-section search on log T between its neighbours.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

struct FirstOrderStepOptions {
  // Search range of the time constant T = m / k in seconds (0 < min < max).
  double min_time_constant = 0.05;
  double max_time_constant = 300.0;
  // Points of the log grid (>= 2) before the golden-section refinement.
  int grid = 200;

  bool IsValid(std::string* error) const;
};

struct FirstOrderStepFit {
  double time_constant = 0.0;  // T, seconds
  double gain = 0.0;           // k = du / (y_after - y_before), the linearised damping (seed: k_i)
  double inertia = 0.0;        // m = k T
  double rms = 0.0;            // of the fit residual y_k - y(t_k), signal units
  int samples = 0;             // samples used (t_k >= t_step, y_k not NaN)
  bool at_bound = false;       // T is an end of the search range: the true T may lie outside
};

// Fits the step response above to the samples (t_k, y_k) with t_k >= t_step; NaN samples are
// skipped. The caller passes the samples of the step's interval (up to the next input change)
// and the steady values before and after it. k and hence m may be negative if the data say so
// (e.g. a response against the input); they are reported as computed and the caller filters.
// False with a message for invalid options, mismatched sizes, non-finite arguments, a zero
// response change y_after - y_before, a zero input change, or fewer than 3 usable samples.
bool FitFirstOrderStep(const std::vector<double>& t, const std::vector<double>& y, double t_step,
                       double y_before, double y_after, double input_change,
                       const FirstOrderStepOptions& options, FirstOrderStepFit* fit,
                       std::string* error);

}  // namespace vesselid
