#include "engine/step_regression/step_regression_bootstrap.h"

#include <algorithm>
#include <map>

#include "engine/step_regression/term_regression.h"

namespace vesselid {
namespace {

// The replicate's set: each sample repeated as often as its group was drawn; copy c of a
// group gets its own id (distinct CV groups when the regression selects lambda again).
SampleSet DrawSet(const SampleSet& set, const std::map<int, int>& index,
                  const std::vector<int>& counts) {
  SampleSet drawn;
  int copies = 0;
  for (int c : counts) copies = std::max(copies, c);
  for (int copy = 0; copy < copies; ++copy) {
    for (size_t i = 0; i < set.y.size(); ++i) {
      const int g = index.at(set.group[i]);
      if (counts[g] <= copy) continue;
      drawn.x.push_back(set.x[i]);
      drawn.y.push_back(set.y[i]);
      drawn.w.push_back(set.w[i]);
      drawn.group.push_back(g + copy * static_cast<int>(counts.size()));
    }
  }
  return drawn;
}

// The term refitted at the full fit's normalisation, lambda and (a, b).
bool RefitHeld(const DampingInertiaForm& form, const SampleSet& set, bool inertia,
               const StepRegressionOptions& options, TermRegression* term) {
  const int nb = form.num_basis();
  const int columns = nb + (inertia ? 1 : 0);
  if (static_cast<int>(set.y.size()) <= columns) return false;
  const int s = form.asymptote_state;
  const double a_n = term->a * term->sd_x[s], b_n = (term->b - term->mean_x[s]) / term->sd_x[s];
  const Eigen::MatrixXd x = Regressors(form.degree, set, *term, inertia, s, a_n, b_n);
  Eigen::VectorXd y, w;
  NormalisedTarget(set, *term, &y, &w);
  const LassoOptions lasso = TermLassoOptions(options, columns);
  term->normalised = FitLasso(x, y, w, term->lambda, lasso, &term->normalised);
  term->coefficients =
      ExpandToModelBasis(form.degree, form.scale.data(), term->mean_x, term->sd_x, term->mean_y,
                         term->sd_y, term->normalised.head(nb));
  if (inertia) term->coefficients.push_back(term->sd_y * term->normalised[nb]);
  return true;
}

// Parameter indices of term t's coefficients (model basis order, then the tanh amplitude).
const std::vector<int>& TermParameters(const DampingInertiaForm& form, int t) {
  return t < 2 ? form.damping[t] : form.inertia[t - 2];
}

}  // namespace

bool BootstrapStepRegression(const DampingInertiaForm& form, const StepRegressionReport& report,
                             const StepRegressionOptions& options,
                             const std::vector<std::string>& parameter_names,
                             BootstrapSummary* bootstrap, std::string* error) {
  const GroupBootstrapOptions& b = options.bootstrap;
  const std::array<SampleSet, 4> sets = TermSampleSets(report.samples);
  // Strata: damping groups (sets 0 and 1 hold the same samples), then each inertia set's.
  std::map<int, int> index[3];
  std::vector<int> strata;
  for (int k = 0; k < 3; ++k) {
    for (int g : sets[k == 0 ? 0 : k + 1].group) index[k].emplace(g, 0);
    int n = 0;
    for (auto& [id, i] : index[k]) i = n++;
    strata.push_back(n);
  }
  // Quantities: the form's coefficients, and a, b when selected again.
  std::vector<int> quantities;
  for (int t = 0; t < 4; ++t) {
    for (int p : TermParameters(form, t)) quantities.push_back(p);
  }
  if (!b.hold_lambda) {
    for (int i = 0; i < 2; ++i) {
      quantities.push_back(form.asymptote_a[i]);
      quantities.push_back(form.asymptote_b[i]);
    }
  }
  std::vector<std::string> names, coefficient_names;
  for (int p : quantities) names.push_back(parameter_names[p]);
  for (int t = 0; t < 4; ++t) {  // penalised: all but the intercept
    const std::vector<int>& p = TermParameters(form, t);
    for (size_t k = 1; k < p.size(); ++k) coefficient_names.push_back(parameter_names[p[k]]);
  }

  auto replicate = [&](const std::vector<int>& counts, std::vector<double>* values,
                       std::vector<double>* coefficients) {
    StepRegressionReport r;
    r.terms = report.terms;
    for (int t = 0; t < 4; ++t) {
      const int k = t < 2 ? 0 : t - 1;
      int first = 0;
      for (int j = 0; j < k; ++j) first += strata[j];
      const std::vector<int> drawn(counts.begin() + first, counts.begin() + first + strata[k]);
      const SampleSet set = DrawSet(sets[t], index[k], drawn);
      TermRegression& term = r.terms[t];
      if (b.hold_lambda) {
        if (!RefitHeld(form, set, t >= 2, options, &term)) return false;
      } else {
        TermRegression fresh;
        fresh.name = term.name;
        Normalise(set, &fresh);
        std::string ignored;
        if (!RegressTerm(form, set, t >= 2, options, &fresh, &ignored)) return false;
        term = std::move(fresh);
      }
      for (int c = 1; c < term.normalised.size(); ++c) coefficients->push_back(term.normalised[c]);
    }
    std::vector<double> p(parameter_names.size(), 0.0);
    StoreStepRegression(form, r, &p);
    for (int q : quantities) values->push_back(p[q]);
    return true;
  };
  if (!RunGroupBootstrap(strata, names, coefficient_names, replicate, b, bootstrap, error)) {
    return false;
  }
  bootstrap->resampled = "steady-state groups and steps";
  return true;
}

}  // namespace vesselid
