#include "engine/regression/least_squares.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ceres/ceres.h"
#include "engine/base/nan.h"
#include "nlopt.hpp"

namespace vesselid {
namespace {

// Which parameters a regression coefficient depends on, found by perturbation about a point
// where every parameter is distinct and non-zero (products with a zero would hide it).
Eigen::MatrixXi Dependence(const ModelHandle& model, int num_parameters, int num_coefficients) {
  std::vector<double> p(num_parameters), theta0(num_coefficients), theta1(num_coefficients);
  for (int i = 0; i < num_parameters; ++i) p[i] = 1.0 + 0.137 * i;
  model.Coefficients(p.data(), theta0.data());
  Eigen::MatrixXi depends = Eigen::MatrixXi::Zero(num_coefficients, num_parameters);
  for (int i = 0; i < num_parameters; ++i) {
    std::vector<double> q = p;
    q[i] += 0.371;
    model.Coefficients(q.data(), theta1.data());
    for (int j = 0; j < num_coefficients; ++j) depends(j, i) = theta1[j] != theta0[j];
  }
  return depends;
}

// A design column of an equation: coefficient j of the equation, on the samples of every
// record (group -1) or only of the records of one experiment (a per-experiment parameter's
// coefficient: one column per experiment, e.g. the intercept K delta_0/T of each run).
struct DesignColumn {
  int coefficient;
  int group;
};

// The regression problem of every equation at parameters p.
class EquationData {
 public:
  EquationData(const ModelHandle& model, const LeastSquaresOptions& options)
      : model_(model), form_(*model.regression_form()), options_(options) {
    for (const auto& coefficients : form_.coefficients) {
      design_.emplace_back();
      for (int j = 0; j < static_cast<int>(coefficients.size()); ++j) {
        design_.back().push_back({j, -1});
      }
    }
  }

  // Coefficients with expanded[i][j] get one column per group; group_of[r] is record r's.
  void SetGroups(const std::vector<std::vector<bool>>& expanded, int groups,
                 std::vector<int> group_of) {
    group_of_ = std::move(group_of);
    for (size_t i = 0; i < design_.size(); ++i) {
      design_[i].clear();
      for (int j = 0; j < static_cast<int>(expanded[i].size()); ++j) {
        if (!expanded[i][j]) {
          design_[i].push_back({j, -1});
          continue;
        }
        for (int g = 0; g < groups; ++g) design_[i].push_back({j, g});
      }
    }
  }

  const std::vector<DesignColumn>& design(int i) const { return design_[i]; }

  // Stacks the selected samples of each equation: X (the design columns) and y = x'.
  void Build(const std::vector<double>& p, std::vector<RegressionRecord>* records) {
    const int equations = static_cast<int>(form_.states.size());
    x_.assign(equations, Eigen::MatrixXd());
    y_.assign(equations, Eigen::VectorXd());
    std::vector<std::vector<Eigen::MatrixXd>> phis(records->size());
    std::vector<int> rows(equations, 0);
    for (size_t r = 0; r < records->size(); ++r) {
      model_.Regressors(p.data(), &(*records)[r], &phis[r]);
      for (int i = 0; i < equations; ++i) rows[i] += Count((*records)[r], r, phis[r][i], i);
    }
    for (int i = 0; i < equations; ++i) {
      x_[i] = Eigen::MatrixXd::Zero(rows[i], design_[i].size());
      y_[i].resize(rows[i]);
      int row = 0;
      for (size_t r = 0; r < records->size(); ++r) {
        const RegressionRecord& record = (*records)[r];
        const int group = group_of_.empty() ? -1 : group_of_[r];
        for (int k = 0; k < record.size(); ++k) {
          if (!Selected(record, phis[r][i], i, k)) continue;
          for (int copy = Multiplicity(r, k); copy > 0; --copy) {
            for (size_t d = 0; d < design_[i].size(); ++d) {
              const DesignColumn& c = design_[i][d];
              if (c.group < 0 || c.group == group) x_[i](row, d) = phis[r][i](k, c.coefficient);
            }
            y_[i](row++) = record.xdot(k, form_.states[i]);
          }
        }
      }
    }
  }

  const Eigen::MatrixXd& x(int i) const { return x_[i]; }
  const Eigen::VectorXd& y(int i) const { return y_[i]; }

  bool Selected(const RegressionRecord& record, const Eigen::MatrixXd& phi, int equation,
                int k) const {
    if (!record.use[k]) return false;
    if (equation < static_cast<int>(options_.regions.size()) &&
        !options_.regions[equation].empty()) {
      bool in = false;
      for (int region : options_.regions[equation]) in |= record.region[k] == region;
      if (!in) return false;
    }
    return std::isfinite(record.xdot(k, form_.states[equation])) && phi.row(k).allFinite();
  }

 private:
  // How often sample k of record r enters (a bootstrap replicate's draw count, else once).
  int Multiplicity(size_t r, int k) const {
    return options_.sample_counts.empty() ? 1 : options_.sample_counts[r][k];
  }

  int Count(const RegressionRecord& record, size_t r, const Eigen::MatrixXd& phi,
            int equation) const {
    int n = 0;
    for (int k = 0; k < record.size(); ++k) {
      if (Selected(record, phi, equation, k)) n += Multiplicity(r, k);
    }
    return n;
  }

  const ModelHandle& model_;
  const RegressionForm& form_;
  const LeastSquaresOptions& options_;
  std::vector<std::vector<DesignColumn>> design_;
  std::vector<int> group_of_;  // per record; empty: no per-experiment parameters
  std::vector<Eigen::MatrixXd> x_;
  std::vector<Eigen::VectorXd> y_;
};

// Minimum-distance residuals L_i^-1 (theta_i(p) - theta_i^) over the identified coefficients.
// The block holds the shared regressed parameters, then each per-experiment parameter's value
// for every group (experiment); a coefficient of group g is evaluated with group g's values.
struct MinimumDistance {
  const ModelHandle* model;
  std::vector<double> base;         // every parameter
  std::vector<int> free;            // shared: indices into base, in the block's order
  std::vector<int> per_experiment;  // indices into base, after `free` in the block, by group
  int groups = 0;
  std::vector<int> coefficient;  // identified coefficient indices (into theta)
  std::vector<int> group;        // their group, -1: every record
  Eigen::VectorXd target;        // their estimates
  Eigen::MatrixXd whitening;     // L^-1 (block diagonal over equations)
  int num_coefficients = 0;

  int size() const { return static_cast<int>(free.size() + per_experiment.size() * groups); }

  bool operator()(double const* const* parameters, double* residuals) const {
    std::vector<double> p = base;
    for (size_t i = 0; i < free.size(); ++i) p[free[i]] = parameters[0][i];
    std::vector<std::vector<double>> theta(groups + 1, std::vector<double>(num_coefficients));
    model->Coefficients(p.data(), theta[0].data());
    for (int g = 0; g < groups; ++g) {
      std::vector<double> q = p;
      for (size_t m = 0; m < per_experiment.size(); ++m) {
        q[per_experiment[m]] = parameters[0][free.size() + m * groups + g];
      }
      model->Coefficients(q.data(), theta[g + 1].data());
    }
    Eigen::VectorXd difference(coefficient.size());
    for (size_t j = 0; j < coefficient.size(); ++j) {
      difference(j) = theta[group[j] + 1][coefficient[j]] - target(j);
    }
    Eigen::Map<Eigen::VectorXd>(residuals, coefficient.size()) = whitening * difference;
    return true;
  }
};

}  // namespace

std::string LeastSquaresSummary::BriefReport() const {
  if (!usable) return "least squares failed: " + message;
  std::string text = "least squares:";
  char part[128];
  for (const EquationSummary& e : equations) {
    std::snprintf(part, sizeof(part), " %s' R2 %.4f (%d samples, %d rejected);", e.state.c_str(),
                  e.r2, e.samples, e.rejected);
    text += part;
  }
  std::snprintf(part, sizeof(part), " %d profile evaluations, %.3f s", profile_evaluations,
                time_seconds);
  return text + part;
}

bool RunLeastSquares(const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                     const LeastSquaresOptions& options, std::vector<RegressionRecord>* records,
                     LeastSquaresResult* result, LeastSquaresSummary* summary) {
  const auto start_time = std::chrono::steady_clock::now();
  *summary = LeastSquaresSummary();
  auto fail = [&](const std::string& what) {
    summary->message = what;
    return false;
  };
  const ModelInfo& info = model.info();
  const RegressionForm* form = model.regression_form();
  if (form == nullptr) return fail("model " + info.name + " has no equation-error form");
  const int np = static_cast<int>(info.parameters.size());
  const int nc = form->num_coefficients();
  const int equations = static_cast<int>(form->states.size());
  if (static_cast<int>(specs.size()) != np) return fail("parameter list does not match model");

  // Roles: profiled (searched), regressed (from the coefficients), held.
  std::vector<double> p(np);
  std::vector<bool> estimated(np, false), profiled(np, false);
  std::vector<int> per_experiment;
  for (int i = 0; i < np; ++i) {
    p[i] = specs[i].start;
    estimated[i] = specs[i].role != ParameterRole::kFixed;
    if (specs[i].role == ParameterRole::kPerExperiment) per_experiment.push_back(i);
  }
  for (int i : form->profiled) profiled[i] = estimated[i];
  const Eigen::MatrixXi depends = Dependence(model, np, nc);
  std::vector<bool> coefficient_free(nc, false);
  for (int j = 0; j < nc; ++j) {
    for (int i = 0; i < np; ++i) coefficient_free[j] = coefficient_free[j] || (depends(j, i) && estimated[i]);
  }
  std::vector<int> regressed, searched;
  for (int i = 0; i < np; ++i) {
    if (!estimated[i]) continue;
    if (profiled[i] && specs[i].role == ParameterRole::kPerExperiment) {
      return fail("parameter '" + info.parameters[i] +
                  "' enters the regressors and cannot be "
                  "per_experiment in a least-squares stage");
    }
    if (profiled[i]) {
      searched.push_back(i);
      continue;
    }
    if (depends.col(i).sum() == 0) {
      return fail("parameter '" + info.parameters[i] +
                  "' does not enter the equation-error form of " + info.name + "; hold it");
    }
    if (specs[i].role != ParameterRole::kPerExperiment) regressed.push_back(i);
  }
  if (regressed.empty() && per_experiment.empty()) return fail("no parameter to regress");

  // Per-experiment parameters: their coefficients get one column per experiment (group).
  std::vector<std::string> groups;
  std::vector<int> group_of;
  EquationData data(model, options);
  if (!per_experiment.empty()) {
    for (const RegressionRecord& record : *records) {
      const auto found = std::find(groups.begin(), groups.end(), record.name);
      group_of.push_back(static_cast<int>(found - groups.begin()));
      if (found == groups.end()) groups.push_back(record.name);
    }
    std::vector<std::vector<bool>> expanded;
    for (int i = 0, c = 0; i < equations; ++i) {
      expanded.emplace_back();
      for (size_t j = 0; j < form->coefficients[i].size(); ++j, ++c) {
        bool by_experiment = false;
        for (int m : per_experiment) by_experiment |= depends(c, m) != 0;
        expanded.back().push_back(by_experiment);
      }
    }
    data.SetGroups(expanded, static_cast<int>(groups.size()), group_of);
  }
  auto column_name = [&](int i, const DesignColumn& c) {
    return form->coefficients[i][c.coefficient] + (c.group < 0 ? "" : "[" + groups[c.group] + "]");
  };

  // Each equation's regression at p; returns sum_i n_i log(RSS_i / n_i).
  std::vector<int> offset(equations + 1, 0);
  for (int i = 0; i < equations; ++i) {
    offset[i + 1] = offset[i] + static_cast<int>(form->coefficients[i].size());
  }
  std::vector<RegressionResult> fits(equations);
  std::vector<std::vector<int>> columns(equations);  // identified coefficient columns
  std::string regression_error;
  auto regress = [&](const std::vector<double>& values, const RegressionOptions& regression,
                     double* objective) {
    data.Build(values, records);
    std::vector<double> theta(nc);
    model.Coefficients(values.data(), theta.data());
    *objective = 0.0;
    for (int i = 0; i < equations; ++i) {
      const Eigen::MatrixXd& x = data.x(i);
      Eigen::VectorXd y = data.y(i);
      columns[i].clear();
      const double largest = x.rows() > 0 && x.cols() > 0 ? x.colwise().norm().maxCoeff() : 0.0;
      for (int j = 0; j < x.cols(); ++j) {
        const int c = offset[i] + data.design(i)[j].coefficient;
        if (!coefficient_free[c]) {
          y -= x.col(j) * theta[c];  // held: to the left-hand side
        } else if (x.col(j).norm() > 1e-9 * largest) {
          columns[i].push_back(j);
        }
      }
      Eigen::MatrixXd xi(x.rows(), columns[i].size());
      for (size_t j = 0; j < columns[i].size(); ++j) xi.col(j) = x.col(columns[i][j]);
      RegressionOptions equation = regression;
      if (regression.penalty != Penalty::kNone &&
          i < static_cast<int>(options.equation_lambda.size())) {
        equation.lambda = options.equation_lambda[i];  // held by a bootstrap replicate
      }
      if (!SolveRegression(xi, y, equation, &fits[i], &regression_error)) {
        regression_error = form->coefficients[i].empty() ? regression_error
                           : "equation " + info.states[form->states[i]] + "': " + regression_error;
        return false;
      }
      const double n = static_cast<double>(y.size());
      const double rss = std::max(fits[i].residual_rms * fits[i].residual_rms * n, 1e-300);
      *objective += n * std::log(rss / n);
    }
    return true;
  };

  // 1. Profiled parameters: bounded search on plain regressions.
  RegressionOptions plain;
  if (!searched.empty()) {
    const int n = static_cast<int>(searched.size());
    nlopt::opt optimizer(nlopt::LN_BOBYQA, n);
    std::vector<double> lower(n), upper(n), z(n);
    for (int k = 0; k < n; ++k) {
      const ParameterSpec& s = specs[searched[k]];
      if (!std::isfinite(s.lower) || !std::isfinite(s.upper)) {
        return fail("parameter '" + s.name + "' is searched (it enters the regressors) and "
                    "needs finite bounds");
      }
      lower[k] = s.lower;
      upper[k] = s.upper;
      z[k] = s.start;
    }
    optimizer.set_lower_bounds(lower);
    optimizer.set_upper_bounds(upper);
    optimizer.set_maxeval(options.max_profile_evaluations);
    optimizer.set_xtol_rel(1e-4);
    struct Context {
      std::function<double(const std::vector<double>&)> f;
    } context;
    bool failed = false;
    context.f = [&](const std::vector<double>& values) {
      std::vector<double> q = p;
      for (int k = 0; k < n; ++k) q[searched[k]] = values[k];
      double objective;
      ++summary->profile_evaluations;
      if (!regress(q, plain, &objective)) {
        failed = true;
        return std::numeric_limits<double>::max();
      }
      return objective;
    };
    optimizer.set_min_objective(
        [](const std::vector<double>& x, std::vector<double>&, void* c) {
          return static_cast<Context*>(c)->f(x);
        },
        &context);
    double best;
    try {
      optimizer.optimize(z, best);
    } catch (const std::exception& e) {
      return fail(std::string("profile search: ") + e.what());
    }
    if (failed && !std::isfinite(best)) return fail(regression_error);
    for (int k = 0; k < n; ++k) p[searched[k]] = z[k];
  }

  // 2. The regressions with the stage's options.
  if (!regress(p, options.regression, &summary->objective)) return fail(regression_error);
  std::vector<double> theta_now(nc);
  model.Coefficients(p.data(), theta_now.data());
  for (int i = 0; i < equations; ++i) {
    EquationSummary e;
    e.state = info.states[form->states[i]];
    const int m = static_cast<int>(data.design(i).size());
    e.theta = Eigen::VectorXd::Constant(m, kNaN);
    e.std_errors = Eigen::VectorXd::Constant(m, kNaN);
    for (int j = 0; j < m; ++j) {
      const DesignColumn& d = data.design(i)[j];
      e.coefficients.push_back(column_name(i, d));
      const int c = offset[i] + d.coefficient;
      if (!coefficient_free[c]) e.theta(j) = theta_now[c];
    }
    e.regressed.assign(m, false);
    for (size_t j = 0; j < columns[i].size(); ++j) {
      e.regressed[columns[i][j]] = true;
      e.theta(columns[i][j]) = fits[i].theta(j);
      e.std_errors(columns[i][j]) = fits[i].std_errors(j);
    }
    e.samples = static_cast<int>(data.y(i).size());
    e.rejected = fits[i].rejected;
    e.lambda = fits[i].lambda;
    e.r2 = fits[i].r2;
    e.residual_rms = fits[i].residual_rms;
    summary->equations.push_back(e);
  }

  // 3. Minimum distance from the coefficients to the regressed parameters.
  auto* distance = new MinimumDistance;
  distance->model = &model;
  distance->base = p;
  distance->free = regressed;
  distance->per_experiment = per_experiment;
  distance->groups = static_cast<int>(groups.size());
  distance->num_coefficients = nc;
  std::vector<Eigen::MatrixXd> blocks;
  int identified = 0;
  for (int i = 0; i < equations; ++i) {
    const int m = static_cast<int>(columns[i].size());
    if (m == 0) continue;
    Eigen::MatrixXd w;
    Eigen::LLT<Eigen::MatrixXd> llt(fits[i].covariance);
    if (fits[i].covariance.rows() == m && fits[i].covariance.allFinite() &&
        llt.info() == Eigen::Success) {
      w = llt.matrixL().solve(Eigen::MatrixXd::Identity(m, m));
    } else if (fits[i].std_errors.size() == m && fits[i].std_errors.allFinite() &&
               (fits[i].std_errors.array() > 0.0).all()) {
      // A covariance not positive definite to rounding: each coefficient at its own standard
      // error (the residual level alone would give every coefficient the same one, whatever
      // its regressor's unit).
      w = fits[i].std_errors.cwiseInverse().asDiagonal();
    } else {  // no covariance (lasso): equal weights at the equation's residual level
      w = Eigen::MatrixXd::Identity(m, m) / std::max(fits[i].residual_rms, 1e-12);
    }
    blocks.push_back(w);
    for (int j = 0; j < m; ++j) {
      const DesignColumn& d = data.design(i)[columns[i][j]];
      distance->coefficient.push_back(offset[i] + d.coefficient);
      distance->group.push_back(d.group);
    }
    identified += m;
  }
  distance->target.resize(identified);
  distance->whitening = Eigen::MatrixXd::Zero(identified, identified);
  {
    int row = 0, b = 0;
    for (int i = 0; i < equations; ++i) {
      const int m = static_cast<int>(columns[i].size());
      if (m == 0) continue;
      distance->target.segment(row, m) = fits[i].theta;
      distance->whitening.block(row, row, m, m) = blocks[b++];
      row += m;
    }
  }
  // The block: shared regressed parameters, then per-experiment ones group by group, each
  // started from its experiment's carried value (ParameterSpec::experiment_starts).
  const int nr = distance->size();
  const int shared = static_cast<int>(regressed.size());
  const int num_groups = static_cast<int>(groups.size());
  std::vector<int> block_parameter(nr);  // model parameter of each block entry
  std::vector<double> block(nr);
  for (int k = 0; k < shared; ++k) {
    block_parameter[k] = regressed[k];
    block[k] = p[regressed[k]];
  }
  for (size_t m = 0; m < per_experiment.size(); ++m) {
    const ParameterSpec& spec = specs[per_experiment[m]];
    for (int g = 0; g < num_groups; ++g) {
      const int k = shared + static_cast<int>(m) * num_groups + g;
      block_parameter[k] = per_experiment[m];
      const auto carried = spec.experiment_starts.find(groups[g]);
      block[k] = carried != spec.experiment_starts.end()
                     ? std::clamp(carried->second, spec.lower, spec.upper)
                     : spec.start;
    }
  }
  auto block_name = [&](int k) {
    const std::string& name = info.parameters[block_parameter[k]];
    return k < shared ? name : name + "[" + groups[(k - shared) % num_groups] + "]";
  };
  auto* cost = new ceres::DynamicNumericDiffCostFunction<MinimumDistance, ceres::CENTRAL>(
      distance, ceres::TAKE_OWNERSHIP);
  cost->AddParameterBlock(nr);
  cost->SetNumResiduals(identified);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, block.data());
  for (int k = 0; k < nr; ++k) {
    const ParameterSpec& s = specs[block_parameter[k]];
    if (std::isfinite(s.lower)) problem.SetParameterLowerBound(block.data(), k, s.lower);
    if (std::isfinite(s.upper)) problem.SetParameterUpperBound(block.data(), k, s.upper);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 200;
  solver.function_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-12;
  ceres::Solver::Summary solved;
  ceres::Solve(solver, &problem, &solved);
  if (!solved.IsSolutionUsable()) return fail("minimum distance: " + solved.message);
  for (int k = 0; k < shared; ++k) p[regressed[k]] = block[k];
  for (size_t m = 0; m < per_experiment.size(); ++m) {  // the mean serves the regressors
    double sum = 0.0;
    for (int g = 0; g < num_groups; ++g) sum += block[shared + m * num_groups + g];
    if (num_groups > 0) p[per_experiment[m]] = sum / num_groups;
  }

  // Covariance of the regressed parameters: (J^T J)^-1 over the determined ones.
  double cost_value;
  std::vector<double> jacobian(static_cast<size_t>(identified) * nr);
  double* jacobians[1] = {jacobian.data()};
  std::vector<double> residuals(identified);
  const double* parameters[1] = {block.data()};
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost_value, nullptr, nullptr, nullptr);
  cost->Evaluate(parameters, residuals.data(), jacobians);
  const Eigen::MatrixXd j =
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobian.data(), identified, nr);
  result->values = p;
  result->std_errors.assign(np, kNaN);
  result->undetermined.assign(np, false);
  result->free.clear();
  result->per_experiment.clear();
  std::vector<int> determined;
  for (int k = 0; k < nr; ++k) {
    if (j.col(k).norm() > 1e-12) {
      determined.push_back(k);
    } else {
      if (k < shared) result->undetermined[regressed[k]] = true;
      summary->notes.push_back("'" + block_name(k) +
                               "' enters no identified coefficient (no data in its regions); "
                               "held at its start");
    }
  }
  Eigen::MatrixXd jd(identified, determined.size());
  for (size_t k = 0; k < determined.size(); ++k) jd.col(k) = j.col(determined[k]);
  const Eigen::MatrixXd information = jd.transpose() * jd;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(information);
  Eigen::MatrixXd covariance;
  if (lu.rank() < information.rows()) {
    summary->notes.push_back("the coefficients do not determine every parameter (rank " +
                             std::to_string(lu.rank()) + " of " +
                             std::to_string(information.rows()) + ")");
    covariance = Eigen::MatrixXd::Constant(information.rows(), information.rows(), kNaN);
  } else {
    covariance = information.inverse();
  }
  int determined_shared = 0;
  for (size_t k = 0; k < determined.size(); ++k) {
    if (determined[k] >= shared) continue;
    ++determined_shared;
    const int i = regressed[determined[k]];
    result->free.push_back(i);
    result->std_errors[i] = std::sqrt(covariance(k, k));
  }
  // Determined shared entries come first in `determined`: their block is the covariance.
  result->covariance = covariance.topLeftCorner(determined_shared, determined_shared);
  for (int k = shared; k < nr; ++k) {
    ExperimentValue v;
    v.parameter = block_parameter[k];
    v.experiment = groups[(k - shared) % num_groups];
    v.value = block[k];
    const auto at = std::find(determined.begin(), determined.end(), k);
    v.undetermined = at == determined.end();
    const int row = static_cast<int>(at - determined.begin());
    v.std_error = v.undetermined ? kNaN : std::sqrt(covariance(row, row));
    result->per_experiment.push_back(v);
  }
  for (int i : searched) {
    result->free.push_back(i);  // searched: no standard error from the regression
    summary->notes.push_back("'" + info.parameters[i] + "' searched in [" +
                             std::to_string(specs[i].lower) + ", " +
                             std::to_string(specs[i].upper) + "]: " + std::to_string(p[i]));
    // A search that ends on a bound is an at_bound finding (diagnose/), from the estimate.
  }
  data.Build(p, records);  // leaves the internal states of the records at the final values
  summary->usable = true;
  summary->time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return true;
}

bool OneStepMetrics(const ModelHandle& model, const std::vector<double>& p,
                    const LeastSquaresOptions& options, std::vector<RegressionRecord>* records,
                    const std::string& label, std::vector<ChannelMetrics>* metrics,
                    std::string* error) {
  const RegressionForm* form = model.regression_form();
  if (form == nullptr) {
    *error = "model " + model.info().name + " has no equation-error form";
    return false;
  }
  const int equations = static_cast<int>(form->states.size());
  std::vector<double> theta(form->num_coefficients());
  model.Coefficients(p.data(), theta.data());
  std::vector<MetricAccumulator> accumulators(equations);
  EquationData data(model, options);
  for (RegressionRecord& record : *records) {
    std::vector<Eigen::MatrixXd> phi;
    model.Regressors(p.data(), &record, &phi);
    int offset = 0;
    for (int i = 0; i < equations; ++i) {
      const int m = static_cast<int>(form->coefficients[i].size());
      const Eigen::Map<const Eigen::VectorXd> theta_i(theta.data() + offset, m);
      const int s = form->states[i];
      for (int k = 0; k + 1 < record.size(); ++k) {
        if (!data.Selected(record, phi[i], i, k)) continue;
        const double step = record.t[k + 1] - record.t[k];
        const double predicted = record.x(k, s) + step * phi[i].row(k).dot(theta_i);
        accumulators[i].Add(predicted, record.x(k + 1, s));
      }
      offset += m;
    }
  }
  metrics->clear();
  for (int i = 0; i < equations; ++i) {
    metrics->push_back(accumulators[i].Finish(label, model.info().states[form->states[i]]));
  }
  return true;
}

}  // namespace vesselid
