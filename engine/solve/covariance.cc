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

// More free variables than this, some of them per experiment: the covariance by blocks
// (covariance.h), whatever the budget. The dense SVD is O(n^3) (seconds at 1 000, hours at
// 20 000), and nobody reads the correlations of thousands of initial states.
constexpr int kDenseVariables = 1000;
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

// The covariance by blocks (covariance.h): the shared variables' covariance and correlation,
// each per-experiment variable's standard error. `n` and `m`: free variables and residuals.
bool BlockUncertainty(const OutputErrorProblem& problem, double final_cost,
                      const SolutionJacobian& solution, int m, int n, Uncertainty* u) {
  const std::vector<Variable>& variables = problem.variables();
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[i] = variables[solution.variables[i]].experiment;
  const ArrowBlocks arrow = ArrowQrBlocks(solution.jacobian, group);
  const int ns = static_cast<int>(arrow.shared_columns.size());
  const double decision = RankDecisionTolerance(m, n);
  const double tolerance = std::max(kRankTolerance, decision);
  // Shared block: column norms of J (every block's R_gp rows and R_pp), R_pp D^-1's SVD.
  Eigen::VectorXd norms = Eigen::VectorXd::Zero(ns);
  for (const ArrowBlocks::Block& b : arrow.blocks) {
    norms += b.shared.colwise().squaredNorm().transpose();
  }
  if (ns > 0) norms += arrow.shared.colwise().squaredNorm().transpose();
  norms = norms.cwiseSqrt();
  for (int j = 0; j < ns; ++j) {
    if (!(norms[j] > 0)) norms[j] = 1.0;
  }
  u->variables.clear();
  for (int c : arrow.shared_columns) u->variables.push_back(solution.variables[c]);
  Eigen::MatrixXd c_pp = Eigen::MatrixXd::Zero(ns, ns);  // (R_pp^T R_pp)^+, normalised back
  if (ns > 0) {
    const Eigen::MatrixXd rn = arrow.shared * norms.cwiseInverse().asDiagonal();
    Eigen::BDCSVD<Eigen::MatrixXd> svd(rn, Eigen::ComputeThinV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    const Eigen::MatrixXd& v = svd.matrixV();
    const bool deficient = !(sigma[ns - 1] > decision * sigma[0]);
    Eigen::MatrixXd pseudo = Eigen::MatrixXd::Zero(ns, ns);
    for (int k = 0; k < ns; ++k) {
      if (deficient && !(sigma[k] > tolerance * sigma[0])) continue;
      pseudo += v.col(k) * v.col(k).transpose() / (sigma[k] * sigma[k]);
    }
    if (deficient) NameUndetermined(problem, sigma, v, norms, tolerance, u);
    c_pp = norms.cwiseInverse().asDiagonal() * pseudo * norms.cwiseInverse().asDiagonal();
  }
  // A likelihood (the filter-error method) is its own scale: J'J is the Fisher information.
  u->residual_variance = problem.filter_error() ? 1.0 : 2.0 * final_cost / (m - n);
  Eigen::VectorXd scales(ns);
  for (int j = 0; j < ns; ++j) scales[j] = variables[u->variables[j]].scale;
  u->covariance = u->residual_variance * scales.asDiagonal() * c_pp * scales.asDiagonal();
  SetStdErrorsAndCorrelation(u);
  // Each group's variances: rows of R_gg^-1 and of B = R_gg^-1 R_gp through C_pp. A group
  // whose own block is singular (a diagonal of R_gg below the rank tolerance of its column)
  // leaves its variables undetermined.
  int undetermined_groups = 0;
  for (const ArrowBlocks::Block& b : arrow.blocks) {
    const int nl = static_cast<int>(b.columns.size());
    bool singular = false;
    for (int k = 0; k < nl; ++k) {
      const double column = b.own.col(k).norm() + b.shared.row(k).norm();
      singular |= !(std::abs(b.own(k, k)) > tolerance * column);
    }
    Eigen::VectorXd variance =
        Eigen::VectorXd::Constant(nl, std::numeric_limits<double>::quiet_NaN());
    if (!singular) {
      const auto r = b.own.triangularView<Eigen::Upper>();
      const Eigen::MatrixXd a = r.solve(Eigen::MatrixXd::Identity(nl, nl));
      const Eigen::MatrixXd bp = r.solve(b.shared);
      variance = a.rowwise().squaredNorm() + (bp * c_pp).cwiseProduct(bp).rowwise().sum();
    } else {
      ++undetermined_groups;
    }
    for (int i = 0; i < nl; ++i) {
      const int index = solution.variables[b.columns[i]];
      const double scale = variables[index].scale;
      u->block_variables.push_back(index);
      u->block_std_errors.push_back(
          singular ? std::numeric_limits<double>::quiet_NaN()
                   : std::sqrt(std::max(0.0, u->residual_variance * variance[i])) * scale);
      if (singular) u->undetermined_variables.push_back(index);
    }
  }
  char text[300];
  std::snprintf(text, sizeof(text),
                "the covariance of the %d shared variable(s) only, with the standard errors of "
                "the %zu per-experiment ones without their correlations (all of them at once: ",
                ns, u->block_variables.size());
  const double dense = 8.0 * sizeof(double) * n * static_cast<double>(n);
  u->message =
      text +
      (dense > static_cast<double>(MemoryBudget())
           ? OverBudget("the covariance of " + std::to_string(n) + " free variables", dense)
           : "the covariance of " + std::to_string(n) + " free variables, more than " +
                 std::to_string(kDenseVariables) + ", is not formed") +
      ")";
  if (!u->undetermined.empty()) {
    u->message += "; the Jacobian is rank deficient: the data do not determine " +
                  std::to_string(u->undetermined.size()) +
                  " combination(s) of the shared variables";
  }
  if (undetermined_groups > 0) {
    u->message += "; " + std::to_string(undetermined_groups) +
                  " experiment(s) do not determine their own variables";
  }
  return true;
}

}  // namespace

double Uncertainty::StdError(int index) const {
  for (size_t i = 0; i < variables.size(); ++i) {
    if (variables[i] == index)
      return i < std_errors.size() ? std_errors[i] : std::numeric_limits<double>::quiet_NaN();
  }
  for (size_t i = 0; i < block_variables.size(); ++i) {
    if (block_variables[i] == index) return block_std_errors[i];
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
      // A covariance that is not positive semi-definite in floating point (the sandwich of
      // a near-singular Hessian) can give |c| > 1: the pair is correlated to round-off.
      if (i != j) {
        u->correlation(i, j) =
            d > 0 ? std::clamp(u->covariance(i, j) / d, -1.0, 1.0) : 0.0;
      }
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
  // covariance and the correlation. Over the budget: by blocks, in the shared variables'
  // s x s matrices and each group's (own + s) numbers per own variable.
  const double dense = 8.0 * sizeof(double) * static_cast<double>(n) * n;
  int own = 0;  // free variables of one experiment (initial states, per-experiment values)
  for (int v : u->variables) own += variables[v].experiment >= 0 ? 1 : 0;
  const bool by_blocks =
      dense > static_cast<double>(MemoryBudget()) || (own > 0 && n > kDenseVariables);
  if (by_blocks) {
    const double shared = n - own;
    const double blocks = sizeof(double) * (8.0 * shared * shared + 4.0 * own * (shared + 8.0));
    if (blocks > static_cast<double>(MemoryBudget())) {
      u->message = "not computed: " +
                   OverBudget("the covariance of " + std::to_string(n) + " free variables (" +
                                  std::to_string(own) + " of them per experiment)",
                              blocks);
      return false;
    }
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
  if (by_blocks) {
    const bool done = BlockUncertainty(*problem, final_cost, *solution, m, n, u);
    u->available = done;
    return done;
  }
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
  u->residual_variance = problem->filter_error() ? 1.0 : 2.0 * final_cost / (m - n);
  Eigen::VectorXd scales(n);
  for (int i = 0; i < n; ++i) scales[i] = variables[u->variables[i]].scale;
  u->covariance = u->residual_variance * scales.asDiagonal() * c * scales.asDiagonal();
  SetStdErrorsAndCorrelation(u);
  u->available = true;
  return true;
}

}  // namespace vesselid
