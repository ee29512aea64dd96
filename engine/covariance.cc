#include "engine/covariance.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "ceres/covariance.h"

namespace vesselid {
namespace {

// Null-space directions of J (scaled by column norms) from a dense SVD, named.
std::vector<std::string> UndeterminedDirections(OutputErrorProblem* problem,
                                                const std::vector<int>& variables) {
  ceres::Problem::EvaluateOptions options;
  for (int index : variables) options.parameter_blocks.push_back(problem->variables()[index].block);
  ceres::CRSMatrix crs;
  std::vector<std::string> names;
  if (!problem->problem()->Evaluate(options, nullptr, nullptr, nullptr, &crs)) return names;
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r) {
    for (int k = crs.rows[r]; k < crs.rows[r + 1]; ++k) jacobian(r, crs.cols[k]) = crs.values[k];
  }
  Eigen::VectorXd norms = jacobian.colwise().norm();
  for (int c = 0; c < norms.size(); ++c) {
    if (norms[c] > 0) jacobian.col(c) /= norms[c];
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  for (int k = 0; k < sigma.size(); ++k) {
    if (sigma[k] > 1e-7 * sigma[0]) continue;
    std::string text;
    for (int c = 0; c < sigma.size(); ++c) {
      double weight = svd.matrixV()(c, k);
      if (std::abs(weight) < 0.05) continue;
      char term[128];
      std::snprintf(term, sizeof(term), "%s%.2f %s", text.empty() ? "" : " + ", weight,
                    problem->variables()[variables[c]].name.c_str());
      text += term;
    }
    names.push_back(text);
  }
  return names;
}

}  // namespace

double Uncertainty::StdError(int index) const {
  for (size_t i = 0; i < variables.size(); ++i) {
    if (variables[i] == index) return std_errors[i];
  }
  return std::numeric_limits<double>::quiet_NaN();
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
  if (!covariance.Compute(blocks, problem->problem())) {
    u->undetermined = UndeterminedDirections(problem, u->variables);
    u->message = "the Jacobian is rank deficient: the data do not determine every free variable";
    return false;
  }
  Eigen::MatrixXd c(n, n);
  covariance.GetCovarianceMatrix(blocks, c.data());
  u->residual_variance = 2.0 * final_cost / (m - n);
  Eigen::VectorXd scales(n);
  for (int i = 0; i < n; ++i) scales[i] = variables[u->variables[i]].scale;
  u->covariance = u->residual_variance * scales.asDiagonal() * c * scales.asDiagonal();
  u->std_errors.resize(n);
  for (int i = 0; i < n; ++i) u->std_errors[i] = std::sqrt(std::max(0.0, u->covariance(i, i)));
  u->correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double d = u->std_errors[i] * u->std_errors[j];
      if (i != j) u->correlation(i, j) = d > 0 ? u->covariance(i, j) / d : 0.0;
    }
  }
  u->available = true;
  return true;
}

}  // namespace vesselid
