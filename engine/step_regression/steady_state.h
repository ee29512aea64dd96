// Steady states of a step-response record (seed 004, Eriksen & Breivik, §3.3 "Extraction of
// damping data"): the record is split into intervals of constant input, and the tail of each
// interval on which the measured signals have settled is averaged. At steady state the model
// M(x) x' + sigma(x) = tau gives sigma(x) = tau (seed eq. 5), so each steady window yields one
// damping measurement (mean x, constant tau).
//
// Settle rule, per interval [begin, end) and signal i (NaN samples are missing and skipped):
//
//   ybar_i(k)  centred moving average of y_i over the rows j of the interval with
//              |t_j - t_k| <= smoothing / 2 (the window is cut at the interval's ends)
//   H          the interval's last half: rows with t_j >= (t_begin + t_end) / 2
//   ref_i      mean of y_i over H
//   band_i     max(tolerance_i, band_factor * SD_i), SD_i the sample SD of y_i over H
//   violates   row k violates if |ybar_i(k) - ref_i| > band_i for some testable signal i
//   steady_begin = 1 + the last violating row (begin if none)
//
// i.e. t_steady is the first time after which every smoothed signal stays inside its band
// around its settled (last-half) value for the rest of the interval. The window is steady if
// t_end - t_steady >= min_duration. A signal is testable in an interval if it has samples in H.
// A row whose averaging window has samples of y_i in fewer than half of its rows (in or next to
// a gap) is not tested for signal i: such an average is nearly as noisy as a raw sample.
//
// The window starts with a residual transient of up to about band_i, decaying with the time
// constant T, so its mean is biased towards the previous level by up to about band_i T / W
// (W = t_end - t_steady); with band 2 noise SDs that is a few standard errors of the mean for
// W of 10 T. Smaller band_factor (in the absence of oscillations) or longer holds reduce it.
//
// Why an SD band around the last-half mean: with an ocean current the speed over ground
// oscillates with the turn period while circling at steady state (the seed holds each level
// for a full turn and averages). SD_i over H measures that oscillation plus noise, and a band of
// 2 SD around the mean holds a sinusoid of amplitude A (SD = A / sqrt 2, band = 1.41 A); a
// fixed band, or one around the value at the very end (which may sit on a crest), would not.
// Limitation: a signal still drifting in the last half widens its own band, so a level held
// for too short a time may be called steady early; hold levels for several time constants
// plus the averaging window, as the seed's experiment design does.
//
// Cost: O(n s) per record (prefix sums and two pointers for the moving averages).
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {

struct SteadyStateOptions {
  // An input differing from the interval's first row by more than this (in any column) starts a
  // new interval.
  double input_tolerance = 1e-6;
  // Width in seconds of the centred moving average the settle test looks at; 0: raw samples.
  double smoothing = 5.0;
  // band_i = max(tolerance_i, band_factor * SD_i), SD_i of signal i over the interval's last
  // half (oscillation about the steady value plus noise).
  double band_factor = 2.0;
  // Per signal, the absolute floor of the band (signal units); empty: 0 for every signal.
  std::vector<double> tolerance;
  // Seconds; a steady window shorter than this (t_end - t_steady) is not steady.
  double min_duration = 10.0;

  bool IsValid(std::string* error) const;
};

struct InputInterval {
  int begin = 0, end = 0;     // rows [begin, end) with constant inputs
  double t_begin = 0.0;       // time of row begin
  double t_end = 0.0;         // time of row end - 1
  std::vector<double> input;  // the constant inputs (q), row begin's values
  bool steady = false;        // a steady window of at least min_duration was found
  // The settle test's window is rows [steady_begin, end); set even when it is too short to be
  // steady (steady_begin = end when no signal could be tested).
  int steady_begin = 0;
  double t_steady = 0.0;         // time of row steady_begin (t_end if steady_begin = end)
  std::vector<double> mean, sd;  // per signal over the window (NaN when not steady or no data)
  std::vector<double> band;      // per signal, the band the settle test used (NaN: untestable)
};

// Splits the record into constant-input intervals and finds the steady window at the end of
// each with the settle rule above. t: n strictly increasing finite times; signals: n x s
// (s >= 1, NaN = missing, no infinities); inputs: n x q (q >= 1, finite). False with a message
// for invalid options, mismatched sizes, non-finite inputs or times, or non-increasing t.
bool FindSteadyStates(const std::vector<double>& t, const Eigen::MatrixXd& signals,
                      const Eigen::MatrixXd& inputs, const SteadyStateOptions& options,
                      std::vector<InputInterval>* intervals, std::string* error);

}  // namespace vesselid
