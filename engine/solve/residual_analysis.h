// Residual analysis of one output channel, as MATLAB's `resid`: whether the residuals
// e = simulated - measured are white and independent of past inputs, as the Hessian standard
// errors s^2 (J^T J)^-1 assume. Lag k is k samples of the channel's own sequence.
//
//   autocorrelation   r_k = c_k / c_0, c_k = 1/N sum_{t=1..N-k} (e_t - mean e)(e_{t+k} - mean e),
//                     k = 0..L, L = min(25, N / 5);
//   band              +-z / sqrt(N): z = 2.58 (99 %) and 1.96 (95 %), where r_k of white
//                     residuals lies at each lag;
//   Ljung-Box         Q = N (N + 2) sum_{k=1..L} r_k^2 / (N - k) ~ chi2_L for white residuals,
//                     p = P(chi2_L > Q); "white" when p >= kWhitenessLevel (0.01);
//   cross-correlation r_eu(k) = c_eu(k) / sqrt(c_ee(0) c_uu(0)),
//                     c_eu(k) = 1/N sum_t (e_{t+k} - mean e)(u_t - mean u), k = -L..L:
//                     k >= 0 correlates the residual with past inputs; its 99 % band is
//                     MATLAB's, 2.58 sqrt(sum_{|k|<=L} r_ee(k) r_uu(k)) / sqrt(N) (Bartlett),
//                     +-2.58 / sqrt(N) for white residuals and wider for coloured ones, so that
//                     a coloured residual alone does not look input-correlated;
//                     "input-correlated" when some |r_eu(k)| > band at k >= 0.
// O(N L) time; no per-lag allocation.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace vesselid {

inline constexpr int kResidualMaxLags = 25;
inline constexpr double kWhitenessLevel = 0.01;     // Ljung-Box p below it: coloured

inline constexpr double kBand99 = 2.5758293035489;  // two-sided normal quantiles
inline constexpr double kBand95 = 1.9599639845401;
// Fewer samples than this: no test (too few lags to say anything).
inline constexpr int kResidualMinSamples = 10;
// Sample intervals spread more than this around their median: lags are sample indices, not
// a fixed time (noted as irregular sampling).
inline constexpr double kIrregularSpacing = 0.1;

// Cross-correlation of the residuals with one model input.
struct ResidualCrossCorrelation {
  std::string input;
  std::vector<double> values;  // lags -L..L (NaN throughout for a constant input)
  double band_99 = 0.0;        // Bartlett band, see above
  bool correlated = false;     // some |value| > band_99 at lag >= 0
};

struct ResidualAnalysis {
  std::string experiment, output;
  int samples = 0;
  int lags = 0;                         // L; 0 when there were too few samples to test
  std::vector<double> autocorrelation;  // r_0 = 1, ..., r_L
  double band_99 = 0.0, band_95 = 0.0;  // +-z / sqrt(N)
  double ljung_box_q = std::numeric_limits<double>::quiet_NaN();
  double ljung_box_p = std::numeric_limits<double>::quiet_NaN();
  double lag1 = std::numeric_limits<double>::quiet_NaN();
  bool white = true;  // also when untested (lags == 0)
  std::vector<ResidualCrossCorrelation> cross_correlation;
  bool input_correlated = false;
  // Largest |dt - median dt| / median dt of the channel's sample times.
  double interval_spread = 0.0;
  // The data have no noise to speak of (noise-free synthetic data): the residuals are the
  // integration's error, smooth and so coloured, and say nothing of measurement noise
  // (NoiseFree below); reported, not warned.
  bool noise_free = false;
  // The largest share of the residual power that noise on a measured input can make (99 %
  // quantile over the input noise refits, input_noise_uncertainty.h); 0 when no input was
  // found noisy.
  double input_noise_share = 0.0;
  // The series are a filter's normalised innovations (the filter-error method), not a free
  // run's residuals.
  bool innovations = false;

  bool tested() const { return lags > 0; }
  // What the coloured_residuals finding says: whiteness rejected (Ljung-Box) and the lag-1
  // autocorrelation itself beyond the 99 % band; a rejection at far lags with a lag-1 of 0.00
  // is not what a reader takes "coloured" for.
  bool coloured() const { return tested() && !white && std::abs(lag1) > band_99; }
  bool irregular() const { return interval_spread > kIrregularSpacing; }
};

// A fit to noise-free data: RMS residual below kNoiseFreeNoiseRatio times the data's own
// noise level (second differences, noise_level.h; on noise-free data that is the signal's
// curvature) and 1 - R^2 below kNoiseFreeUnexplained (numerical precision). Real noise keeps
// the RMS residual near or above the noise level, so that both never hold for measured data.
inline constexpr double kNoiseFreeNoiseRatio = 0.1;
inline constexpr double kNoiseFreeUnexplained = 1e-10;
inline bool NoiseFree(double rmse, double noise, double r2) {
  return rmse < kNoiseFreeNoiseRatio * noise && 1.0 - r2 < kNoiseFreeUnexplained;
}

// L for N samples: min(kResidualMaxLags, N / 5); 0 below kResidualMinSamples.
int ResidualLags(int samples);

// r_0..r_max_lag of `e` (mean removed); all NaN when e is constant.
std::vector<double> Autocorrelation(const std::vector<double>& e, int max_lag);

// r_eu(-max_lag..max_lag) as above (e and u of the same length); NaN when either is constant.
std::vector<double> CrossCorrelation(const std::vector<double>& e, const std::vector<double>& u,
                                     int max_lag);

// Ljung-Box Q of r_1..r_L of a series of n samples.
double LjungBoxQ(const std::vector<double>& autocorrelation, int n);

// The whole analysis of one channel: residuals `e` at sample times `t` (may be empty: regular),
// inputs[i] named input_names[i] at the same samples.
ResidualAnalysis AnalyseResiduals(const std::string& experiment, const std::string& output,
                                  const std::vector<double>& t, const std::vector<double>& e,
                                  const std::vector<std::string>& input_names,
                                  const std::vector<std::vector<double>>& inputs);

}  // namespace vesselid
