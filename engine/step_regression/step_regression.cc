#include "engine/step_regression/step_regression.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/base/elapsed.h"
#include "engine/step_regression/term_regression.h"

namespace vesselid {

void Normalise(const SampleSet& set, TermRegression* term) {
  const double n = static_cast<double>(set.y.size());
  for (int c = 0; c < 2; ++c) {
    double mean = 0.0, square = 0.0;
    for (const auto& x : set.x) mean += x[c] / n;
    for (const auto& x : set.x) square += (x[c] - mean) * (x[c] - mean) / n;
    term->mean_x[c] = mean;
    term->sd_x[c] = square > 0.0 ? std::sqrt(square) : 1.0;
  }
  double mean = 0.0, square = 0.0;
  for (double y : set.y) mean += y / n;
  for (double y : set.y) square += (y - mean) * (y - mean) / n;
  term->mean_y = mean;
  term->sd_y = square > 0.0 ? std::sqrt(square) : 1.0;
}

// Normalised regressors: the polynomial basis, then (inertia) the asymptotic term.
void NormalisedTarget(const SampleSet& set, const TermRegression& term, Eigen::VectorXd* y,
                      Eigen::VectorXd* w) {
  y->resize(set.y.size());
  w->resize(set.y.size());
  for (size_t i = 0; i < set.y.size(); ++i) {
    (*y)[i] = (set.y[i] - term.mean_y) / term.sd_y;
    (*w)[i] = set.w[i];
  }
}

LassoOptions TermLassoOptions(const StepRegressionOptions& options, int columns) {
  LassoOptions lasso = options.lasso;
  lasso.penalty_factors = Eigen::VectorXd::Ones(columns);
  lasso.penalty_factors[0] = 0.0;  // intercept
  return lasso;
}

Eigen::MatrixXd Regressors(int degree, const SampleSet& set, const TermRegression& term,
                           bool asymptote, int asymptote_state, double a_n, double b_n) {
  const int nb = NumMonomials(degree);
  Eigen::MatrixXd x(set.y.size(), nb + (asymptote ? 1 : 0));
  std::vector<double> phi(nb);
  for (size_t i = 0; i < set.y.size(); ++i) {
    const double z0 = (set.x[i][0] - term.mean_x[0]) / term.sd_x[0];
    const double z1 = (set.x[i][1] - term.mean_x[1]) / term.sd_x[1];
    Monomials(degree, z0, z1, phi.data());
    for (int k = 0; k < nb; ++k) x(i, k) = phi[k];
    if (asymptote) x(i, nb) = std::tanh(a_n * ((asymptote_state == 0 ? z0 : z1) - b_n));
  }
  return x;
}

bool RegressTerm(const DampingInertiaForm& form, const SampleSet& set, bool inertia,
                 const StepRegressionOptions& options, TermRegression* term,
                 std::string* error) {
  const auto start = SteadyClock::now();
  const int nb = form.num_basis();
  const int columns = nb + (inertia ? 1 : 0);
  term->samples = static_cast<int>(set.y.size());
  std::vector<int> ids = set.group;
  std::sort(ids.begin(), ids.end());
  term->groups = static_cast<int>(std::unique(ids.begin(), ids.end()) - ids.begin());
  if (term->samples <= columns || term->groups < 3) {
    *error = term->name + ": " + std::to_string(term->samples) + " samples in " +
             std::to_string(term->groups) + " groups for " + std::to_string(columns) +
             " coefficients (more steady states or steps are needed)";
    return false;
  }
  Eigen::VectorXd y, w;
  NormalisedTarget(set, *term, &y, &w);
  const LassoOptions lasso = TermLassoOptions(options, columns);
  const int s = form.asymptote_state;
  std::vector<std::pair<double, double>> grid = {{0.0, 0.0}};
  if (inertia) {
    grid.clear();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& x : set.x) {
      lo = std::min(lo, x[s]);
      hi = std::max(hi, x[s]);
    }
    const int nbp = options.asymptote_b_points;
    for (double a : options.asymptote_a) {
      for (int j = 0; j < nbp; ++j) {
        grid.push_back({a, nbp == 1 ? 0.5 * (lo + hi) : lo + (hi - lo) * j / (nbp - 1)});
      }
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : grid) {
    const double a_n = a * term->sd_x[s], b_n = (b - term->mean_x[s]) / term->sd_x[s];
    const Eigen::MatrixXd x = Regressors(form.degree, set, *term, inertia, s, a_n, b_n);
    LassoPath path;
    if (!CrossValidateLasso(x, y, w, set.group, lasso, &path, error)) {
      *error = term->name + ": " + *error;
      return false;
    }
    const double cv = path.cv_error[path.best];
    if (inertia) term->asymptote_grid.push_back({a, b, cv, path.lambda[path.best]});
    if (cv < best) {
      best = cv;
      term->a = a;
      term->b = b;
      term->path = std::move(path);
    }
  }
  term->lambda = term->path.lambda[term->path.best];
  term->normalised = term->path.beta.row(term->path.best).transpose();

  // Fit on the samples in physical units.
  const double a_n = term->a * term->sd_x[s], b_n = (term->b - term->mean_x[s]) / term->sd_x[s];
  const Eigen::MatrixXd x = Regressors(form.degree, set, *term, inertia, s, a_n, b_n);
  const Eigen::VectorXd fitted =
      (x * term->normalised).array() * term->sd_y + term->mean_y;
  double mean = 0.0, total = 0.0, residual = 0.0, weight = w.sum();
  for (size_t i = 0; i < set.y.size(); ++i) mean += w[i] * set.y[i] / weight;
  for (size_t i = 0; i < set.y.size(); ++i) {
    total += w[i] * (set.y[i] - mean) * (set.y[i] - mean);
    residual += w[i] * (set.y[i] - fitted[i]) * (set.y[i] - fitted[i]);
  }
  term->r2 = total > 0.0 ? 1.0 - residual / total : std::numeric_limits<double>::quiet_NaN();
  term->rms = std::sqrt(residual / weight);

  term->coefficients =
      ExpandToModelBasis(form.degree, form.scale.data(), term->mean_x, term->sd_x, term->mean_y,
                         term->sd_y, term->normalised.head(nb));
  if (inertia) term->coefficients.push_back(term->sd_y * term->normalised[nb]);
  term->seconds = SecondsSince(start);
  return true;
}

std::array<SampleSet, 4> TermSampleSets(const StepSamples& samples) {
  std::array<SampleSet, 4> sets;
  for (const DampingSample& s : samples.damping) {
    for (int i = 0; i < 2; ++i) {
      sets[i].x.push_back({s.x[0], s.x[1]});
      sets[i].y.push_back(s.sigma[i]);
      sets[i].w.push_back(s.weight);
      sets[i].group.push_back(s.group);
    }
  }
  for (int i = 0; i < 2; ++i) {
    for (const InertiaSample& s : samples.inertia[i]) {
      sets[2 + i].x.push_back({s.x[0], s.x[1]});
      sets[2 + i].y.push_back(s.inertia);
      sets[2 + i].w.push_back(s.weight);
      sets[2 + i].group.push_back(s.group);
    }
  }
  return sets;
}

bool StepRegressionOptions::IsValid(const DampingInertiaForm& form, std::string* error) const {
  if (!samples.IsValid(form, error)) return false;
  if (asymptote_a.empty() || asymptote_b_points < 1) {
    *error = "step regression: the asymptote grid is empty";
    return false;
  }
  for (double a : asymptote_a) {
    if (!(a > 0.0)) {
      *error = "step regression: asymptote a values must be > 0";
      return false;
    }
  }
  return true;
}

std::vector<double> ExpandToModelBasis(int degree, const double* scale, const double* mean_x,
                                       const double* sd_x, double mean_y, double sd_y,
                                       const Eigen::VectorXd& b) {
  const int nb = NumMonomials(degree);
  const int side = degree + 3;
  Eigen::MatrixXd model(side * side, nb);
  Eigen::VectorXd target(side * side);
  std::vector<double> phi(nb);
  int row = 0;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j, ++row) {
      const double x0 = mean_x[0] + sd_x[0] * (-2.0 + 4.0 * i / (side - 1));
      const double x1 = mean_x[1] + sd_x[1] * (-2.0 + 4.0 * j / (side - 1));
      Monomials(degree, (x0 - mean_x[0]) / sd_x[0], (x1 - mean_x[1]) / sd_x[1], phi.data());
      target[row] = mean_y;
      for (int k = 0; k < nb; ++k) target[row] += sd_y * b[k] * phi[k];
      Monomials(degree, x0 / scale[0], x1 / scale[1], phi.data());
      for (int k = 0; k < nb; ++k) model(row, k) = phi[k];
    }
  }
  const Eigen::VectorXd c = model.colPivHouseholderQr().solve(target);
  return std::vector<double>(c.data(), c.data() + nb);
}

bool RunStepRegression(const DampingInertiaForm& form,
                       const std::vector<RegressionRecord>& records,
                       const StepRegressionOptions& options, StepRegressionReport* report,
                       std::string* error) {
  if (!options.IsValid(form, error)) return false;
  StepRegressionReport r;
  if (!ExtractStepSamples(form, records, options.samples, &r.samples, error)) return false;

  auto start = SteadyClock::now();
  const std::array<SampleSet, 4> sets = TermSampleSets(r.samples);
  r.terms.resize(4);
  for (int t = 0; t < 4; ++t) {
    r.terms[t].name = t < static_cast<int>(form.term_names.size()) ? form.term_names[t]
                                                                    : "term" + std::to_string(t);
    if (!sets[t].y.empty()) Normalise(sets[t], &r.terms[t]);
  }
  r.normalisation_seconds = SecondsSince(start);

  start = SteadyClock::now();
  for (int t = 0; t < 4; ++t) {
    if (!RegressTerm(form, sets[t], t >= 2, options, &r.terms[t], error)) return false;
  }
  r.regression_seconds = SecondsSince(start);
  *report = std::move(r);
  return true;
}

void StoreStepRegression(const DampingInertiaForm& form, const StepRegressionReport& report,
                         std::vector<double>* parameters) {
  for (int i = 0; i < 2; ++i) {
    const TermRegression& sigma = report.terms[i];
    const TermRegression& m = report.terms[2 + i];
    for (size_t k = 0; k < form.damping[i].size(); ++k) {
      (*parameters)[form.damping[i][k]] = sigma.coefficients[k];
    }
    for (size_t k = 0; k < form.inertia[i].size(); ++k) {
      (*parameters)[form.inertia[i][k]] = m.coefficients[k];
    }
    (*parameters)[form.asymptote_a[i]] = m.a;
    (*parameters)[form.asymptote_b[i]] = m.b;
  }
}

}  // namespace vesselid
