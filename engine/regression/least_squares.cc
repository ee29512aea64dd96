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

// One least-squares stage's work (RunLeastSquares): the parameters' roles, the equation data,
// each equation's regression, the profile search, the minimum distance from the identified
// coefficients to the parameters and the parameters' covariance.
class LeastSquaresRun {
 public:
  LeastSquaresRun(const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                  const LeastSquaresOptions& options, std::vector<RegressionRecord>* records,
                  LeastSquaresSummary* summary)
      : model_(model), info_(model.info()), form_(*model.regression_form()), specs_(specs),
        options_(options), records_(records), summary_(summary), data_(model, options),
        np_(static_cast<int>(info_.parameters.size())), nc_(form_.num_coefficients()),
        equations_(static_cast<int>(form_.states.size())), fits_(equations_),
        columns_(equations_), offset_(equations_ + 1, 0) {
    for (int i = 0; i < equations_; ++i) {
      offset_[i + 1] = offset_[i] + static_cast<int>(form_.coefficients[i].size());
    }
  }

  // Roles: profiled (searched), regressed (from the coefficients), held; per-experiment
  // parameters' coefficients get one column per experiment (group).
  bool Roles() {
    if (static_cast<int>(specs_.size()) != np_) return Fail("parameter list does not match model");
    p_.resize(np_);
    std::vector<bool> estimated(np_, false), profiled(np_, false);
    for (int i = 0; i < np_; ++i) {
      p_[i] = specs_[i].start;
      estimated[i] = specs_[i].role != ParameterRole::kFixed;
      if (specs_[i].role == ParameterRole::kPerExperiment) per_experiment_.push_back(i);
    }
    for (int i : form_.profiled) profiled[i] = estimated[i];
    depends_ = Dependence(model_, np_, nc_);
    coefficient_free_.assign(nc_, false);
    for (int j = 0; j < nc_; ++j) {
      for (int i = 0; i < np_; ++i) coefficient_free_[j] = coefficient_free_[j] || (depends_(j, i) && estimated[i]);
    }
    for (int i = 0; i < np_; ++i) {
      if (!estimated[i]) continue;
      if (profiled[i] && specs_[i].role == ParameterRole::kPerExperiment) {
        return Fail("parameter '" + info_.parameters[i] +
                    "' enters the regressors and cannot be "
                    "per_experiment in a least-squares stage");
      }
      if (profiled[i]) {
        searched_.push_back(i);
        continue;
      }
      if (depends_.col(i).sum() == 0) {
        return Fail("parameter '" + info_.parameters[i] +
                    "' does not enter the equation-error form of " + info_.name + "; hold it");
      }
      if (specs_[i].role != ParameterRole::kPerExperiment) regressed_.push_back(i);
    }
    if (regressed_.empty() && per_experiment_.empty()) return Fail("no parameter to regress");
    if (!per_experiment_.empty()) SetGroups();
    return true;
  }

  // 1. The profiled parameters searched (BOBYQA within their bounds) on plain regressions.
  bool Profile() {
    if (searched_.empty()) return true;
    const int n = static_cast<int>(searched_.size());
    nlopt::opt optimizer(nlopt::LN_BOBYQA, n);
    std::vector<double> lower(n), upper(n), z(n);
    for (int k = 0; k < n; ++k) {
      const ParameterSpec& s = specs_[searched_[k]];
      if (!std::isfinite(s.lower) || !std::isfinite(s.upper)) {
        return Fail("parameter '" + s.name + "' is searched (it enters the regressors) and "
                    "needs finite bounds");
      }
      lower[k] = s.lower;
      upper[k] = s.upper;
      z[k] = s.start;
    }
    optimizer.set_lower_bounds(lower);
    optimizer.set_upper_bounds(upper);
    optimizer.set_maxeval(options_.max_profile_evaluations);
    optimizer.set_xtol_rel(1e-4);
    struct Context {
      std::function<double(const std::vector<double>&)> f;
    } context;
    bool failed = false;
    const RegressionOptions plain;
    context.f = [&](const std::vector<double>& values) {
      std::vector<double> q = p_;
      for (int k = 0; k < n; ++k) q[searched_[k]] = values[k];
      double objective;
      ++summary_->profile_evaluations;
      if (!Regress(q, plain, &objective)) {
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
      return Fail(std::string("profile search: ") + e.what());
    }
    if (failed && !std::isfinite(best)) return Fail(regression_error_);
    for (int k = 0; k < n; ++k) p_[searched_[k]] = z[k];
    return true;
  }

  // 2. The regressions with the stage's options, summarised equation by equation.
  bool Regressions() {
    if (!Regress(p_, options_.regression, &summary_->objective)) return Fail(regression_error_);
    std::vector<double> theta_now(nc_);
    model_.Coefficients(p_.data(), theta_now.data());
    for (int i = 0; i < equations_; ++i) {
      EquationSummary e;
      e.state = info_.states[form_.states[i]];
      const int m = static_cast<int>(data_.design(i).size());
      e.theta = Eigen::VectorXd::Constant(m, kNaN);
      e.std_errors = Eigen::VectorXd::Constant(m, kNaN);
      for (int j = 0; j < m; ++j) {
        const DesignColumn& d = data_.design(i)[j];
        e.coefficients.push_back(form_.coefficients[i][d.coefficient] +
                                 (d.group < 0 ? "" : "[" + groups_[d.group] + "]"));
        const int c = offset_[i] + d.coefficient;
        if (!coefficient_free_[c]) e.theta(j) = theta_now[c];
      }
      e.regressed.assign(m, false);
      for (size_t j = 0; j < columns_[i].size(); ++j) {
        e.regressed[columns_[i][j]] = true;
        e.theta(columns_[i][j]) = fits_[i].theta(j);
        e.std_errors(columns_[i][j]) = fits_[i].std_errors(j);
      }
      e.samples = static_cast<int>(data_.y(i).size());
      e.rejected = fits_[i].rejected;
      e.lambda = fits_[i].lambda;
      e.r2 = fits_[i].r2;
      e.residual_rms = fits_[i].residual_rms;
      summary_->equations.push_back(e);
    }
    return true;
  }

  // 3. The regressed parameters (shared, then per experiment group by group) nearest to the
  // identified coefficients in their covariance's metric, and their covariance.
  bool Distance(LeastSquaresResult* result) {
    MinimumDistance* distance = NewDistance();
    const int identified = static_cast<int>(distance->target.size());
    const int nr = distance->size();
    StartBlock(nr);
    auto* cost = new ceres::DynamicNumericDiffCostFunction<MinimumDistance, ceres::CENTRAL>(
        distance, ceres::TAKE_OWNERSHIP);
    cost->AddParameterBlock(nr);
    cost->SetNumResiduals(identified);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, block_.data());
    for (int k = 0; k < nr; ++k) {
      const ParameterSpec& s = specs_[block_parameter_[k]];
      if (std::isfinite(s.lower)) problem.SetParameterLowerBound(block_.data(), k, s.lower);
      if (std::isfinite(s.upper)) problem.SetParameterUpperBound(block_.data(), k, s.upper);
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = 200;
    solver.function_tolerance = 1e-14;
    solver.parameter_tolerance = 1e-12;
    ceres::Solver::Summary solved;
    ceres::Solve(solver, &problem, &solved);
    if (!solved.IsSolutionUsable()) return Fail("minimum distance: " + solved.message);
    const int shared = static_cast<int>(regressed_.size());
    const int num_groups = static_cast<int>(groups_.size());
    for (int k = 0; k < shared; ++k) p_[regressed_[k]] = block_[k];
    for (size_t m = 0; m < per_experiment_.size(); ++m) {  // the mean serves the regressors
      double sum = 0.0;
      for (int g = 0; g < num_groups; ++g) sum += block_[shared + m * num_groups + g];
      if (num_groups > 0) p_[per_experiment_[m]] = sum / num_groups;
    }
    // The Jacobian of the whitened distance at the solution.
    double cost_value;
    std::vector<double> jacobian(static_cast<size_t>(identified) * nr);
    double* jacobians[1] = {jacobian.data()};
    std::vector<double> residuals(identified);
    const double* parameters[1] = {block_.data()};
    problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost_value, nullptr, nullptr, nullptr);
    cost->Evaluate(parameters, residuals.data(), jacobians);
    Covariance(Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
                   jacobian.data(), identified, nr),
               result);
    return true;
  }

  // Notes on the searched parameters; the records' internal states left at the final values.
  void Finish() {
    for (int i : searched_) {
      summary_->notes.push_back("'" + info_.parameters[i] + "' searched in [" +
                                std::to_string(specs_[i].lower) + ", " +
                                std::to_string(specs_[i].upper) + "]: " + std::to_string(p_[i]));
      // A search that ends on a bound is an at_bound finding (diagnose/), from the estimate.
    }
    data_.Build(p_, records_);
  }

 private:
  bool Fail(const std::string& what) {
    summary_->message = what;
    return false;
  }

  // Per-experiment parameters: their coefficients get one column per experiment (group).
  void SetGroups() {
    std::vector<int> group_of;
    for (const RegressionRecord& record : *records_) {
      const auto found = std::find(groups_.begin(), groups_.end(), record.name);
      group_of.push_back(static_cast<int>(found - groups_.begin()));
      if (found == groups_.end()) groups_.push_back(record.name);
    }
    std::vector<std::vector<bool>> expanded;
    for (int i = 0, c = 0; i < equations_; ++i) {
      expanded.emplace_back();
      for (size_t j = 0; j < form_.coefficients[i].size(); ++j, ++c) {
        bool by_experiment = false;
        for (int m : per_experiment_) by_experiment |= depends_(c, m) != 0;
        expanded.back().push_back(by_experiment);
      }
    }
    data_.SetGroups(expanded, static_cast<int>(groups_.size()), group_of);
  }

  // Each equation's regression at `values`; `objective` = sum_i n_i log(RSS_i / n_i).
  bool Regress(const std::vector<double>& values, const RegressionOptions& regression,
               double* objective) {
    data_.Build(values, records_);
    std::vector<double> theta(nc_);
    model_.Coefficients(values.data(), theta.data());
    *objective = 0.0;
    for (int i = 0; i < equations_; ++i) {
      const Eigen::MatrixXd& x = data_.x(i);
      Eigen::VectorXd y = data_.y(i);
      columns_[i].clear();
      const double largest = x.rows() > 0 && x.cols() > 0 ? x.colwise().norm().maxCoeff() : 0.0;
      for (int j = 0; j < x.cols(); ++j) {
        const int c = offset_[i] + data_.design(i)[j].coefficient;
        if (!coefficient_free_[c]) {
          y -= x.col(j) * theta[c];  // held: to the left-hand side
        } else if (x.col(j).norm() > 1e-9 * largest) {
          columns_[i].push_back(j);
        }
      }
      Eigen::MatrixXd xi(x.rows(), columns_[i].size());
      for (size_t j = 0; j < columns_[i].size(); ++j) xi.col(j) = x.col(columns_[i][j]);
      RegressionOptions equation = regression;
      if (regression.penalty != Penalty::kNone &&
          i < static_cast<int>(options_.equation_lambda.size())) {
        equation.lambda = options_.equation_lambda[i];  // held by a bootstrap replicate
      }
      if (!SolveRegression(xi, y, equation, &fits_[i], &regression_error_)) {
        regression_error_ = form_.coefficients[i].empty()
                                ? regression_error_
                                : "equation " + info_.states[form_.states[i]] + "': " + regression_error_;
        return false;
      }
      const double n = static_cast<double>(y.size());
      const double rss = std::max(fits_[i].residual_rms * fits_[i].residual_rms * n, 1e-300);
      *objective += n * std::log(rss / n);
    }
    return true;
  }

  // The equation's whitening: the inverse Cholesky factor of its coefficients' covariance.
  Eigen::MatrixXd Whitening(int i) const {
    const int m = static_cast<int>(columns_[i].size());
    const RegressionResult& fit = fits_[i];
    Eigen::LLT<Eigen::MatrixXd> llt(fit.covariance);
    if (fit.covariance.rows() == m && fit.covariance.allFinite() && llt.info() == Eigen::Success) {
      return llt.matrixL().solve(Eigen::MatrixXd::Identity(m, m));
    }
    if (fit.std_errors.size() == m && fit.std_errors.allFinite() &&
        (fit.std_errors.array() > 0.0).all()) {
      // A covariance not positive definite to rounding: each coefficient at its own standard
      // error (the residual level alone would give every coefficient the same one, whatever
      // its regressor's unit).
      return fit.std_errors.cwiseInverse().asDiagonal();
    }
    // No covariance (lasso): equal weights at the equation's residual level.
    return Eigen::MatrixXd::Identity(m, m) / std::max(fit.residual_rms, 1e-12);
  }

  // The distance from the identified coefficients, whitened equation by equation.
  MinimumDistance* NewDistance() const {
    auto* distance = new MinimumDistance;
    distance->model = &model_;
    distance->base = p_;
    distance->free = regressed_;
    distance->per_experiment = per_experiment_;
    distance->groups = static_cast<int>(groups_.size());
    distance->num_coefficients = nc_;
    int identified = 0;
    for (int i = 0; i < equations_; ++i) {
      for (int j : columns_[i]) {
        const DesignColumn& d = data_.design(i)[j];
        distance->coefficient.push_back(offset_[i] + d.coefficient);
        distance->group.push_back(d.group);
      }
      identified += static_cast<int>(columns_[i].size());
    }
    distance->target.resize(identified);
    distance->whitening = Eigen::MatrixXd::Zero(identified, identified);
    for (int i = 0, row = 0; i < equations_; ++i) {
      const int m = static_cast<int>(columns_[i].size());
      if (m == 0) continue;
      distance->target.segment(row, m) = fits_[i].theta;
      distance->whitening.block(row, row, m, m) = Whitening(i);
      row += m;
    }
    return distance;
  }

  // The block's start: shared regressed parameters at their values, then per-experiment ones
  // group by group, each from its experiment's carried value (ParameterSpec::experiment_starts).
  void StartBlock(int nr) {
    const int shared = static_cast<int>(regressed_.size());
    const int num_groups = static_cast<int>(groups_.size());
    block_parameter_.assign(nr, 0);
    block_.assign(nr, 0.0);
    for (int k = 0; k < shared; ++k) {
      block_parameter_[k] = regressed_[k];
      block_[k] = p_[regressed_[k]];
    }
    for (size_t m = 0; m < per_experiment_.size(); ++m) {
      const ParameterSpec& spec = specs_[per_experiment_[m]];
      for (int g = 0; g < num_groups; ++g) {
        const int k = shared + static_cast<int>(m) * num_groups + g;
        block_parameter_[k] = per_experiment_[m];
        const auto carried = spec.experiment_starts.find(groups_[g]);
        block_[k] = carried != spec.experiment_starts.end()
                        ? std::clamp(carried->second, spec.lower, spec.upper)
                        : spec.start;
      }
    }
  }

  std::string BlockName(int k) const {
    const int shared = static_cast<int>(regressed_.size());
    const std::string& name = info_.parameters[block_parameter_[k]];
    return k < shared ? name : name + "[" + groups_[(k - shared) % groups_.size()] + "]";
  }

  // Covariance of the regressed parameters from the distance's Jacobian `j`: (J^T J)^-1 over
  // the determined ones; the result's values, standard errors and per-experiment values.
  void Covariance(const Eigen::MatrixXd& j, LeastSquaresResult* result) {
    const int nr = static_cast<int>(j.cols());
    const int shared = static_cast<int>(regressed_.size());
    const int num_groups = static_cast<int>(groups_.size());
    result->values = p_;
    result->std_errors.assign(np_, kNaN);
    result->undetermined.assign(np_, false);
    result->free.clear();
    result->per_experiment.clear();
    std::vector<int> determined;
    for (int k = 0; k < nr; ++k) {
      if (j.col(k).norm() > 1e-12) {
        determined.push_back(k);
      } else {
        if (k < shared) result->undetermined[regressed_[k]] = true;
        summary_->notes.push_back("'" + BlockName(k) +
                                  "' enters no identified coefficient (no data in its regions); "
                                  "held at its start");
      }
    }
    Eigen::MatrixXd jd(j.rows(), determined.size());
    for (size_t k = 0; k < determined.size(); ++k) jd.col(k) = j.col(determined[k]);
    const Eigen::MatrixXd information = jd.transpose() * jd;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(information);
    Eigen::MatrixXd covariance;
    if (lu.rank() < information.rows()) {
      summary_->notes.push_back("the coefficients do not determine every parameter (rank " +
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
      const int i = regressed_[determined[k]];
      result->free.push_back(i);
      result->std_errors[i] = std::sqrt(covariance(k, k));
    }
    // Determined shared entries come first in `determined`: their block is the covariance.
    result->covariance = covariance.topLeftCorner(determined_shared, determined_shared);
    for (int k = shared; k < nr; ++k) {
      ExperimentValue v;
      v.parameter = block_parameter_[k];
      v.experiment = groups_[(k - shared) % num_groups];
      v.value = block_[k];
      const auto at = std::find(determined.begin(), determined.end(), k);
      v.undetermined = at == determined.end();
      const int row = static_cast<int>(at - determined.begin());
      v.std_error = v.undetermined ? kNaN : std::sqrt(covariance(row, row));
      result->per_experiment.push_back(v);
    }
    for (int i : searched_) result->free.push_back(i);  // searched: no standard error
  }

  const ModelHandle& model_;
  const ModelInfo& info_;
  const RegressionForm& form_;
  const std::vector<ParameterSpec>& specs_;
  const LeastSquaresOptions& options_;
  std::vector<RegressionRecord>* records_;
  LeastSquaresSummary* summary_;
  EquationData data_;
  const int np_, nc_, equations_;
  std::vector<double> p_;  // the parameters as the stage goes
  std::vector<int> per_experiment_, regressed_, searched_;
  Eigen::MatrixXi depends_;
  std::vector<bool> coefficient_free_;
  std::vector<std::string> groups_;  // the experiments of per-experiment parameters
  std::vector<RegressionResult> fits_;
  std::vector<std::vector<int>> columns_;  // identified coefficient columns per equation
  std::vector<int> offset_;                // each equation's first coefficient
  std::string regression_error_;
  std::vector<int> block_parameter_;  // the model parameter of each minimum-distance entry
  std::vector<double> block_;
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
  if (model.regression_form() == nullptr) {
    summary->message = "model " + model.info().name + " has no equation-error form";
    return false;
  }
  LeastSquaresRun run(model, specs, options, records, summary);
  // 1. Profiled parameters: bounded search on plain regressions; 2. the regressions with the
  // stage's options; 3. minimum distance from the coefficients to the regressed parameters.
  if (!run.Roles() || !run.Profile() || !run.Regressions() || !run.Distance(result)) return false;
  run.Finish();
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
