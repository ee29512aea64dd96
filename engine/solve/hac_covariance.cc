#include "engine/solve/hac_covariance.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace vesselid {
namespace {

// The quadratic-spectral kernel is summed out to this many bandwidths (its weights decay
// as 1 / x^2 and oscillate; beyond 10 S they are below 0.3 %).
constexpr double kQuadraticSpectralReach = 10.0;

double KernelWeight(HacOptions::Kernel kernel, double x) {
  if (kernel == HacOptions::Kernel::kBartlett) return x < 1.0 ? 1.0 - x : 0.0;
  if (x < 1e-8) return 1.0;
  const double z = 6.0 * M_PI * x / 5.0;
  return 25.0 / (12.0 * M_PI * M_PI * x * x) * (std::sin(z) / z - std::cos(z));
}

// Andrews (1991) AR(1) plug-in: rho_a, sigma_a^2 of an AR(1) per score column, then
//   Bartlett:  S = 1.1447 (alpha(1) T)^(1/3),
//              alpha(1) = sum 4 rho^2 s^4 / ((1-rho)^6 (1+rho)^2) / sum s^4 / (1-rho)^4
//   QS:        S = 1.3221 (alpha(2) T)^(1/5),
//              alpha(2) = sum 4 rho^2 s^4 / (1-rho)^8 / sum s^4 / (1-rho)^4
double PlugInBandwidth(const HacOptions& options, const Eigen::MatrixXd& g) {
  const int t = static_cast<int>(g.rows());
  if (t < 3) return 1.0;
  double numerator = 0.0, denominator = 0.0;
  for (int a = 0; a < g.cols(); ++a) {
    const Eigen::VectorXd lagged = g.col(a).head(t - 1), current = g.col(a).tail(t - 1);
    const double sxx = lagged.squaredNorm();
    if (!(sxx > 0.0)) continue;
    const double rho = std::clamp(current.dot(lagged) / sxx, -options.max_ar, options.max_ar);
    const double s2 = (current - rho * lagged).squaredNorm() / (t - 1);
    const double s4 = s2 * s2;
    denominator += s4 / std::pow(1.0 - rho, 4);
    numerator += options.kernel == HacOptions::Kernel::kBartlett
                     ? 4.0 * rho * rho * s4 / (std::pow(1.0 - rho, 6) * std::pow(1.0 + rho, 2))
                     : 4.0 * rho * rho * s4 / std::pow(1.0 - rho, 8);
  }
  if (!(denominator > 0.0)) return 1.0;
  const double alpha = numerator / denominator;
  const double s = options.kernel == HacOptions::Kernel::kBartlett
                       ? 1.1447 * std::cbrt(alpha * t)
                       : 1.3221 * std::pow(alpha * t, 0.2);
  return std::clamp(s, 1.0, static_cast<double>(t));
}

}  // namespace

const char* HacKernelToString(HacOptions::Kernel kernel) {
  return kernel == HacOptions::Kernel::kBartlett ? "bartlett" : "quadratic_spectral";
}

bool StringToHacKernel(const std::string& text, HacOptions::Kernel* kernel) {
  if (text == "bartlett") {
    *kernel = HacOptions::Kernel::kBartlett;
  } else if (text == "quadratic_spectral") {
    *kernel = HacOptions::Kernel::kQuadraticSpectral;
  } else {
    return false;
  }
  return true;
}

Eigen::MatrixXd LongRunCovariance(const HacOptions& options, const Eigen::MatrixXd& scores,
                                  double* bandwidth) {
  const int n = static_cast<int>(scores.cols());
  const int block = options.aggregation > 0
                        ? options.aggregation
                        : std::max(1, static_cast<int>(std::lround(std::sqrt(scores.rows()))));
  const int blocks = static_cast<int>((scores.rows() + block - 1) / block);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(blocks, n);
  for (int k = 0; k < scores.rows(); ++k) g.row(k / block) += scores.row(k);
  Eigen::MatrixXd recolour = Eigen::MatrixXd::Identity(n, n);
  if (options.prewhiten && blocks > 2 * n + 2) {
    const Eigen::MatrixXd sums = g;
    const int t = blocks;
    const Eigen::MatrixXd lagged = sums.topRows(t - 1), current = sums.bottomRows(t - 1);
    // g_k = Phi g_{k-1} + e_k by least squares: Phi^T = (L^T L)^+ L^T C.
    const Eigen::MatrixXd sxx = lagged.transpose() * lagged;
    const Eigen::MatrixXd sxy = lagged.transpose() * current;
    Eigen::MatrixXd phi = sxx.completeOrthogonalDecomposition().solve(sxy).transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(phi, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd capped = svd.singularValues().cwiseMin(options.max_ar);
    phi = svd.matrixU() * capped.asDiagonal() * svd.matrixV().transpose();
    g = current - lagged * phi.transpose();
    recolour = (Eigen::MatrixXd::Identity(n, n) - phi).inverse();
  }
  const int t = static_cast<int>(g.rows());
  const double s = options.bandwidth > 0.0 ? options.bandwidth : PlugInBandwidth(options, g);
  if (bandwidth != nullptr) *bandwidth = s * block;
  Eigen::MatrixXd omega = g.transpose() * g;
  const int lags =
      options.kernel == HacOptions::Kernel::kBartlett
          ? std::min(t - 1, static_cast<int>(std::ceil(s)) - 1)
          : std::min(t - 1, static_cast<int>(std::ceil(kQuadraticSpectralReach * s)));
  for (int l = 1; l <= lags; ++l) {
    const double w = KernelWeight(options.kernel, l / s);
    if (w == 0.0) continue;
    // Gamma_l = sum_k g_k g_{k-l}^T
    const Eigen::MatrixXd gamma = g.bottomRows(t - l).transpose() * g.topRows(t - l);
    omega += w * (gamma + gamma.transpose());
  }
  return recolour * omega * recolour.transpose();
}

bool ComputeHacCovariance(const HacOptions& options, OutputErrorProblem* problem,
                          const Uncertainty& hessian, Uncertainty* hac,
                          const SolutionJacobian* shared) {
  *hac = Uncertainty();
  hac->method = "sandwich_hac";
  if (!hessian.available) {
    hac->message = "the Hessian covariance is not available: " + hessian.message;
    return false;
  }
  if (!hessian.block_variables.empty()) {
    hac->message = "the Hessian covariance is by blocks (over the memory budget)";
    return false;
  }
  if (!(hessian.residual_variance > 0.0)) {
    hac->message = "the residuals are zero";
    return false;
  }
  const int n = static_cast<int>(hessian.variables.size());
  const std::vector<Variable>& variables = problem->variables();
  SolutionJacobian evaluated;
  if (shared == nullptr || shared->variables != hessian.variables) {
    if (!EvaluateSolutionJacobian(problem, options.num_threads, &evaluated)) {
      hac->message = "the Jacobian could not be evaluated at the solution";
      return false;
    }
    shared = &evaluated;
  }
  // Rows: the experiments' samples in order, then every other block (initial-state priors).
  const std::vector<double>& residuals = shared->residuals;
  const ceres::CRSMatrix& jacobian = shared->jacobian;

  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(n, n);  // B, in scaled variables
  double largest_bandwidth = 0.0;
  int row = 0;
  for (const Experiment& experiment : problem->experiments()) {
    // The experiment's own columns, in order of appearance.
    std::unordered_map<int, int> local;
    std::vector<int> columns;
    for (int r = row; r < row + experiment.num_samples(); ++r) {
      for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
        if (local.emplace(jacobian.cols[k], static_cast<int>(columns.size())).second) {
          columns.push_back(jacobian.cols[k]);
        }
      }
    }
    Eigen::MatrixXd scores = Eigen::MatrixXd::Zero(experiment.num_nodes(), columns.size());
    for (int node = 0; node < experiment.num_nodes(); ++node) {
      for (int i = experiment.node_first_sample[node]; i < experiment.node_first_sample[node + 1];
           ++i) {
        const int r = row + i;
        for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
          scores(node, local[jacobian.cols[k]]) += jacobian.values[k] * residuals[r];
        }
      }
    }
    double bandwidth = 0.0;
    const Eigen::MatrixXd omega = LongRunCovariance(options, scores, &bandwidth);
    largest_bandwidth = std::max(largest_bandwidth, bandwidth);
    for (size_t a = 0; a < columns.size(); ++a) {
      for (size_t b = 0; b < columns.size(); ++b) meat(columns[a], columns[b]) += omega(a, b);
    }
    row += experiment.num_samples();
  }
  for (; row < jacobian.num_rows; ++row) {  // priors: independent, lag 0 only
    for (int a = jacobian.rows[row]; a < jacobian.rows[row + 1]; ++a) {
      for (int b = jacobian.rows[row]; b < jacobian.rows[row + 1]; ++b) {
        meat(jacobian.cols[a], jacobian.cols[b]) +=
            jacobian.values[a] * jacobian.values[b] * residuals[row] * residuals[row];
      }
    }
  }
  // Physical units: with P = s^2 D A^-1 D the Hessian covariance (D the scales),
  //   Cov = D A^-1 B A^-1 D = P D^-1 B D^-1 P / s^4.
  Eigen::VectorXd inverse_scales(n);
  for (int i = 0; i < n; ++i) inverse_scales[i] = 1.0 / variables[hessian.variables[i]].scale;
  const Eigen::MatrixXd& p = hessian.covariance;
  const double s2 = hessian.residual_variance;
  hac->covariance = p * inverse_scales.asDiagonal() * meat * inverse_scales.asDiagonal() * p /
                    (s2 * s2);
  hac->covariance = 0.5 * (hac->covariance + hac->covariance.transpose());
  hac->variables = hessian.variables;
  hac->residual_variance = hessian.residual_variance;
  hac->undetermined = hessian.undetermined;
  hac->undetermined_variables = hessian.undetermined_variables;
  hac->message = hessian.message;
  hac->hac_bandwidth = largest_bandwidth;
  SetStdErrorsAndCorrelation(hac);
  hac->available = true;
  return true;
}

}  // namespace vesselid
