#include "engine/solve/covariance.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "ceres/covariance.h"

namespace vesselid {
namespace {

// Singular values below this fraction of the largest are treated as zero.
constexpr double kRankTolerance = 1e-8;
// A variable takes part in an undetermined direction when its component in the unit
// direction, in physical units or in relative changes (dp / |p|), is at least this large;
// the two views catch both large parameters and small ones that scale along (a thruster
// offset in the force-scale direction).
constexpr double kInvolvedComponent = 0.01;

// Dense Jacobian of the free variables, columns normalised; `norms` gets the column norms.
bool NormalisedJacobian(OutputErrorProblem* problem, const std::vector<int>& variables,
                        Eigen::MatrixXd* jacobian, Eigen::VectorXd* norms) {
  ceres::Problem::EvaluateOptions options;
  for (int index : variables) options.parameter_blocks.push_back(problem->variables()[index].block);
  ceres::CRSMatrix crs;
  if (!problem->problem()->Evaluate(options, nullptr, nullptr, nullptr, &crs)) return false;
  *jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) (*jacobian)(r, crs.cols[k]) = crs.values[k];
  }
  *norms = jacobian->colwise().norm();
  for (int c = 0; c < norms->size(); ++c) {
    if ((*norms)[c] > 0) jacobian->col(c) /= (*norms)[c];
  }
  return true;
}

// Rank-deficient case: names the null-space directions of the normalised Jacobian and forms
// the covariance from the pseudo-inverse over the determined subspace (in theta units).
bool RankDeficientCovariance(OutputErrorProblem* problem, Uncertainty* u, Eigen::MatrixXd* c) {
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd norms;
  if (!NormalisedJacobian(problem, u->variables, &jacobian, &norms)) return false;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const Eigen::MatrixXd& v = svd.matrixV();
  const int n = static_cast<int>(sigma.size());
  std::vector<bool> involved(n, false);
  Eigen::MatrixXd pseudo = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    if (sigma[k] > kRankTolerance * sigma[0]) {
      pseudo += v.col(k) * v.col(k).transpose() / (sigma[k] * sigma[k]);
      continue;
    }
    // The null vector in physical units (dp = dtheta * scale) and as relative changes.
    Eigen::VectorXd physical(n), relative(n);
    for (int i = 0; i < n; ++i) {
      const Variable& var = problem->variables()[u->variables[i]];
      physical[i] = v(i, k) / norms[i] * var.scale;
      const double size = std::abs(var.value());
      relative[i] = physical[i] / (size > 1e-3 * var.scale ? size : var.scale);
    }
    physical.normalize();
    relative.normalize();
    std::string text;
    for (int i = 0; i < n; ++i) {
      if (std::abs(physical[i]) < kInvolvedComponent && std::abs(relative[i]) < kInvolvedComponent)
        continue;
      involved[i] = true;
      char term[160];
      std::snprintf(term, sizeof(term), "%s%+.2g %s", text.empty() ? "" : " ", physical[i],
                    problem->variables()[u->variables[i]].name.c_str());
      text += term;
    }
    u->undetermined.push_back(text);
  }
  for (int i = 0; i < n; ++i) {
    if (involved[i]) u->undetermined_variables.push_back(u->variables[i]);
  }
  const Eigen::VectorXd inverse_norms = norms.cwiseInverse();
  *c = inverse_norms.asDiagonal() * pseudo * inverse_norms.asDiagonal();
  return true;
}

}  // namespace

double Uncertainty::StdError(int index) const {
  for (size_t i = 0; i < variables.size(); ++i) {
    if (variables[i] == index) return std_errors[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void SetStdErrorsAndCorrelation(Uncertainty* u) {
  const int n = static_cast<int>(u->covariance.rows());
  u->std_errors.resize(n);
  for (int i = 0; i < n; ++i) u->std_errors[i] = std::sqrt(std::max(0.0, u->covariance(i, i)));
  for (int index : u->undetermined_variables) {
    for (int i = 0; i < n; ++i) {
      if (u->variables[i] == index) u->std_errors[i] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  u->correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double d = u->std_errors[i] * u->std_errors[j];
      if (i != j) u->correlation(i, j) = d > 0 ? u->covariance(i, j) / d : 0.0;
    }
  }
}

bool ComputeUncertainty(OutputErrorProblem* problem, double final_cost, Uncertainty* u) {
  *u = Uncertainty();
  const std::vector<Variable>& variables = problem->variables();
  std::vector<const double*> blocks;
  for (size_t i = 0; i < variables.size(); ++i) {
    if (!variables[i].free) continue;
    u->variables.push_back(static_cast<int>(i));
    blocks.push_back(variables[i].block);
  }
  const int n = static_cast<int>(blocks.size());
  const int m = problem->num_residuals();
  if (n == 0) {
    u->message = "no free variables";
    return false;
  }
  if (m <= n) {
    u->message = "fewer residuals than free variables";
    return false;
  }
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(options);
  Eigen::MatrixXd c(n, n);
  if (covariance.Compute(blocks, problem->problem())) {
    covariance.GetCovarianceMatrix(blocks, c.data());
  } else if (RankDeficientCovariance(problem, u, &c)) {
    u->message = "the Jacobian is rank deficient: the data do not determine " +
                 std::to_string(u->undetermined.size()) + " combination(s) of the free variables";
  } else {
    u->message = "the Jacobian could not be evaluated at the solution";
    return false;
  }
  u->residual_variance = 2.0 * final_cost / (m - n);
  Eigen::VectorXd scales(n);
  for (int i = 0; i < n; ++i) scales[i] = variables[u->variables[i]].scale;
  u->covariance = u->residual_variance * scales.asDiagonal() * c * scales.asDiagonal();
  SetStdErrorsAndCorrelation(u);
  u->available = true;
  return true;
}

}  // namespace vesselid
