// Latent (noise-free) input from a noisy measured one: a least-squares cubic B-spline on
// uniform knots of spacing h fitted to the samples u_k = s(t_k) + e_k, e_k ~ N(0, sigma^2),
//   min_c  sum_k (u_k - sum_j c_j B_j(t_k))^2 + lambda sum_j (c_j+1 - 2 c_j + c_j-1)^2,
// lambda tiny (it only keeps knot spans without samples determined). The knot spacing is
// chosen among multiples of the sample interval: with sigma unknown by generalised
// cross-validation, GCV(h) = N RSS / (N - m)^2, with sigma given by Mallows' C_p,
// RSS + 2 sigma^2 m (m basis functions). Sigma `auto` is then sqrt(RSS / (N - m)).
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

struct LatentInputOptions {
  double sigma = 0.0;         // noise SD of the samples; 0: estimated
  double knot_spacing = 0.0;  // s; 0: chosen from the data
};

class LatentInputSpline {
 public:
  // Fits `channel` (>= 8 samples, increasing times); false with a message when it cannot.
  bool Fit(const Channel& channel, const LatentInputOptions& options, std::string* error);

  // Values at increasing or arbitrary times (end values held outside the sampled span).
  double operator()(double t) const;
  std::vector<double> At(const std::vector<double>& times) const;

  double sigma() const { return sigma_; }                  // given, or estimated
  double residual_rms() const { return residual_rms_; }    // RMS of u_k - s(t_k)
  double knot_spacing() const { return spacing_; }
  double sample_interval() const { return sample_interval_; }  // median
  int samples() const { return samples_; }

 private:
  double t0_ = 0.0, t1_ = 0.0, spacing_ = 0.0;
  std::vector<double> coefficients_;
  double sigma_ = 0.0, residual_rms_ = 0.0, sample_interval_ = 0.0;
  int samples_ = 0;
};

}  // namespace vesselid
