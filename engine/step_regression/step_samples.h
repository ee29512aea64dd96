// Damping and inertia samples of a damping-inertia model from step-response records (seed 004
// §3.3, "Measurement extraction" and "Data preprocessing"):
//
//   damping: each steady-state window at the end of a constant-input interval gives
//            (x_mean, sigma = tau), since x' = 0 there (eq. (5));
//   inertia: each step of one input tau_i between two steady windows gives m_i = k T from the
//            best-fit first-order response m dx_i' + k dx_i = dtau_i, k = dtau_i / dx_i
//            (eq. (6)), taken at the mid-point of the two steady states.
//
// Preprocessing: damping samples outside the configured input ranges are dropped (seed: the
// motor responds little above tau_m = 0.6); with tau_turn = 0 the turning state is set to
// 0; mirrored copies (x_turn, tau_turn) -> -(x_turn, tau_turn) are added for a craft symmetric
// in yaw. Samples carry a group: steady states of the same input levels in one record (up and
// down steps, and every mirrored copy) form one group, so that leave-one-group-out
// cross-validation never tests on a near-copy of a training sample.
#pragma once

#include <string>
#include <vector>

#include "engine/model/damping_inertia_form.h"
#include "engine/model/regression_form.h"
#include "engine/step_regression/first_order_step.h"
#include "engine/step_regression/steady_state.h"

namespace vesselid {

struct StepSampleOptions {
  // Windows: smoothing, band, min_duration; `steady.tolerance` is per regressed state.
  SteadyStateOptions steady;
  FirstOrderStepOptions step_fit;
  // Per form input: damping samples and steps are kept when its level is inside [lo, hi].
  std::vector<double> input_lower, input_upper;
  // Per regressed state: the smallest change of its steady value that gives an inertia sample.
  std::vector<double> min_change;
  double fit_horizon = 60.0;  // s after a step that its first-order fit uses
  bool zero_straight = true;  // x_turn := 0 on damping samples with tau_turn = 0
  bool mirror = true;
  // Damping weights by the turns a steady window covers (averaging out current and wind):
  // 1 for at least one turn (or a straight run), 0.5 for half a turn, else 0.1 (seed Fig. 8).
  bool turn_weights = true;

  bool IsValid(const DampingInertiaForm& form, std::string* error) const;
};

struct DampingSample {
  std::string record;
  double t = 0.0;          // start of the steady window
  double duration = 0.0;   // of the window, s
  double x[2] = {0, 0};    // regressed states, window mean
  double sigma[2] = {0, 0};  // = the inputs
  double turns = 0.0;
  double weight = 1.0;
  int group = 0;
  bool mirrored = false;
};

struct InertiaSample {
  std::string record;
  int term = 0;            // regressed state whose input stepped
  double t = 0.0;          // step time
  double x[2] = {0, 0};    // mid-point of the steady states before and after
  double inertia = 0.0;    // m = k T
  double gain = 0.0;       // k
  double time_constant = 0.0;
  double rms = 0.0;        // of the first-order fit
  double weight = 1.0;
  int group = 0;
  bool mirrored = false;
};

struct StepSamples {
  std::vector<DampingSample> damping;
  std::vector<InertiaSample> inertia[2];  // per regressed state
  int intervals = 0, steady = 0;          // constant-input intervals, steady ones
  int steps = 0;                          // single-input steps between steady windows
  std::vector<std::string> notes;         // why steps were skipped, summarised
  double window_seconds = 0.0;            // time in FindSteadyStates
  double fit_seconds = 0.0;               // time in the first-order fits
};

bool ExtractStepSamples(const DampingInertiaForm& form,
                        const std::vector<RegressionRecord>& records,
                        const StepSampleOptions& options, StepSamples* samples,
                        std::string* error);

}  // namespace vesselid
