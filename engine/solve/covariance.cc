#include "engine/solve/covariance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/check.h"
#include "engine/base/memory_budget.h"
#include "engine/solve/arrow_qr.h"

namespace vesselid {
namespace {

// Singular values below this fraction of the largest are treated as zero.
constexpr double kRankTolerance = 1e-8;
// A variable takes part in an undetermined direction when its component in the unit
// direction, in physical units or in relative changes (dp / |p|), is at least this large;
// the two views catch both large parameters and small ones that scale along (a thruster
// offset in the force-scale direction).
constexpr double kInvolvedComponent = 0.01;

// Rank is decided as a sparse QR would (SuiteSparseQR's default tolerance, 20 (m + n) eps
// of the largest column norm, here of the largest singular value of the normalised
// Jacobian); only then are the directions below kRankTolerance named undetermined, so that a
// merely ill-conditioned problem keeps its (large) standard errors.
double RankDecisionTolerance(int m, int n) {
  return 20.0 * (m + n) * std::numeric_limits<double>::epsilon();
}

// Names the directions with sigma_k <= tolerance sigma_0 (columns of v, normalised
// coordinates) in physical units and marks the variables taking part.
void NameUndetermined(const OutputErrorProblem& problem, const Eigen::VectorXd& sigma,
                      const Eigen::MatrixXd& v, const Eigen::VectorXd& norms, double tolerance,
                      Uncertainty* u) {
  const int n = static_cast<int>(sigma.size());
  std::vector<bool> involved(n, false);
  for (int k = 0; k < n; ++k) {
    if (sigma[k] > tolerance * sigma[0]) continue;
    // The null vector in physical units (dp = dtheta * scale) and as relative changes.
    Eigen::VectorXd physical(n), relative(n);
    for (int i = 0; i < n; ++i) {
      const Variable& var = problem.variables()[u->variables[i]];
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
                    problem.variables()[u->variables[i]].name.c_str());
      text += term;
    }
    u->undetermined.push_back(text);
  }
  for (int i = 0; i < n; ++i) {
    if (involved[i]) u->undetermined_variables.push_back(u->variables[i]);
  }
}

}  // namespace

double Uncertainty::StdError(int index) const {
  for (size_t i = 0; i < variables.size(); ++i) {
    if (variables[i] == index)
      return i < std_errors.size() ? std_errors[i] : std::numeric_limits<double>::quiet_NaN();
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

bool ComputeUncertainty(OutputErrorProblem* problem, double final_cost, Uncertainty* u,
                        const SolutionJacobian* solution) {
  *u = Uncertainty();
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    if (!variables[i].free) continue;
    u->variables.push_back(static_cast<int>(i));
  }
  const int n = static_cast<int>(u->variables.size());
  const int m = problem->num_residuals();
  if (n == 0) {
    u->message = "no free variables";
    return false;
  }
  if (m <= n) {
    u->message = "fewer residuals than free variables";
    return false;
  }
  // Dense n x n matrices below: R D^-1, the SVD's V and its work, the pseudo-inverse, C, the
  // covariance and the correlation.
  const double dense = 8.0 * sizeof(double) * static_cast<double>(n) * n;
  if (dense > static_cast<double>(MemoryBudget())) {
    int own = 0;  // free variables of one experiment (initial states, per-experiment values)
    for (int v : u->variables) own += variables[v].experiment >= 0 ? 1 : 0;
    u->message = "not computed: " +
                 OverBudget("the covariance of " + std::to_string(n) + " free variables (" +
                                std::to_string(own) + " of them per experiment)",
                            dense);
    return false;
  }
  SolutionJacobian evaluated;
  if (solution == nullptr) {
    if (!EvaluateSolutionJacobian(problem, 1, &evaluated)) {
      u->message = "the Jacobian could not be evaluated at the solution";
      return false;
    }
    solution = &evaluated;
  }
  VESSELID_CHECK(solution->variables == u->variables);
  // R of J (every residual block: data and priors), in normalised coordinates.
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[i] = variables[u->variables[i]].experiment;
  const ArrowR arrow = ArrowQr(solution->jacobian, group);
  Eigen::VectorXd norms(n);  // column norms of J, in J's column order
  Eigen::MatrixXd rn(n, n);  // R D^-1, columns back in J's order
  for (int k = 0; k < n; ++k) {
    const int c = arrow.order[k];
    norms[c] = arrow.r.col(k).norm();
    rn.col(c) = arrow.r.col(k) / (norms[c] > 0 ? norms[c] : 1.0);
    if (!(norms[c] > 0)) norms[c] = 1.0;
  }
  // (J^T J)^+ = D^-1 V S^-2 V^T D^-1 over the determined directions.
  Eigen::BDCSVD<Eigen::MatrixXd> svd(rn, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const Eigen::MatrixXd& v = svd.matrixV();
  const double decision = RankDecisionTolerance(m, n);
  const bool deficient = !(sigma[n - 1] > decision * sigma[0]);
  const double tolerance = std::max(kRankTolerance, decision);
  Eigen::MatrixXd pseudo = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    if (deficient && !(sigma[k] > tolerance * sigma[0])) continue;
    pseudo += v.col(k) * v.col(k).transpose() / (sigma[k] * sigma[k]);
  }
  if (deficient) {
    NameUndetermined(*problem, sigma, v, norms, tolerance, u);
    u->message = "the Jacobian is rank deficient: the data do not determine " +
                 std::to_string(u->undetermined.size()) + " combination(s) of the free variables";
  }
  const Eigen::VectorXd inverse_norms = norms.cwiseInverse();
  const Eigen::MatrixXd c = inverse_norms.asDiagonal() * pseudo * inverse_norms.asDiagonal();
  u->residual_variance = 2.0 * final_cost / (m - n);
  Eigen::VectorXd scales(n);
  for (int i = 0; i < n; ++i) scales[i] = variables[u->variables[i]].scale;
  u->covariance = u->residual_variance * scales.asDiagonal() * c * scales.asDiagonal();
  SetStdErrorsAndCorrelation(u);
  u->available = true;
  return true;
}

}  // namespace vesselid
