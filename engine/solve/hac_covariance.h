// Heteroscedasticity-and-autocorrelation-consistent (HAC) sandwich covariance of an
// output-error estimate, for residuals that are not white (a noisy measured input integrated
// by the model makes the heading residuals a random walk):
//
//   Cov(theta) = A^-1 B A^-1,   A = J^T J,
//   B = sum_e [ Gamma_0 + sum_{l>=1} w(l / S) (Gamma_l + Gamma_l^T) ] + sum_priors g g^T,
//   Gamma_l = sum_k g_k g_{k-l}^T,   g_k = sum over the samples i of node k of J_i^T r_i
//
// per experiment e (experiments are independent; the channels sampled at one time node are
// summed), with r and J the weighted residuals and Jacobian rows Ceres evaluates at the
// optimum (robust-loss corrections included). No s^2: the residuals carry the noise.
// The scores are first summed over blocks of consecutive nodes (aggregation), the lags l
// then count blocks. Kernel w: Bartlett (Newey-West) or quadratic spectral; bandwidth S
// automatic from the Andrews (1991) AR(1) plug-in. With prewhitening (Andrews & Monahan
// 1992; off by default: it overstated the spread 1.5-3x on noisy-rudder records) a VAR(1),
// g_k = Phi g_{k-1} + e_k, is fitted per experiment (Phi's singular values capped), the HAC
// taken of e, and recoloured: Omega = (I - Phi)^-1 Omega_e (I - Phi)^-T.
//
// A^-1 is the Hessian covariance's (covariance.h: pseudo-inverse and undetermined directions
// when J is rank deficient) divided by its s^2. Scores are accumulated per experiment over its
// own columns: memory O(nodes x local columns), never a dense residuals x variables matrix.
#pragma once

#include <string>

#include "Eigen/Dense"
#include "engine/solve/covariance.h"
#include "engine/solve/solution_jacobian.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct HacOptions {
  enum class Kernel { kBartlett, kQuadraticSpectral };
  Kernel kernel = Kernel::kBartlett;
  // Scores summed over consecutive blocks of this many time nodes before the kernel (the
  // long-run covariance of the sums is that of the scores): a slow component under white
  // noise (a random walk under heading noise) shows at the block lags, where it is hidden
  // at the node lags the plug-in looks at. 0: automatic, round(sqrt(nodes)); 1: none.
  int aggregation = 0;
  // Kernel bandwidth S in blocks (Bartlett: S - 1 lags, weights 1 - l / S); 0: automatic
  // (Andrews AR(1) plug-in).
  double bandwidth = 0.0;
  bool prewhiten = false;  // VAR(1) prewhitening and recolouring
  // Cap on the singular values of the prewhitening VAR(1) matrix (and the plug-in's AR(1)
  // coefficients): (I - Phi)^-1 stays finite for a near unit root.
  double max_ar = 0.97;
  int num_threads = 1;  // for the Jacobian evaluation
};

const char* HacKernelToString(HacOptions::Kernel kernel);  // "bartlett", "quadratic_spectral"
bool StringToHacKernel(const std::string& text, HacOptions::Kernel* kernel);

// Long-run covariance sum_l w(l/S) Gamma_l of a score series (rows: time nodes), as above,
// after aggregation and with prewhitening if asked; `bandwidth` (may be null) gets the S used
// in time nodes (S times the block length).
Eigen::MatrixXd LongRunCovariance(const HacOptions& options, const Eigen::MatrixXd& scores,
                                  double* bandwidth);

// HAC covariance of the problem at its current values, given the Hessian uncertainty
// computed there; `hac` gets method "sandwich_hac". False (with hac->message) when the
// Jacobian cannot be evaluated or the Hessian's is not available. `shared` (may be null): the
// residuals and Jacobian already evaluated there (over the Hessian's variables).
bool ComputeHacCovariance(const HacOptions& options, OutputErrorProblem* problem,
                          const Uncertainty& hessian, Uncertainty* hac,
                          const SolutionJacobian* shared = nullptr);

}  // namespace vesselid
