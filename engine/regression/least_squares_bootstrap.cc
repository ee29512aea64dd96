#include "engine/regression/least_squares_bootstrap.h"

#include <cmath>

namespace vesselid {
namespace {

// Every estimated quantity of a fit in a fixed order (shared parameters in model order, then
// the per-experiment values) and whether it is determined.
void Quantities(const std::vector<ParameterSpec>& specs, const LeastSquaresResult& fit,
                std::vector<std::string>* names, std::vector<double>* values,
                std::vector<bool>* determined) {
  for (size_t i = 0; i < specs.size(); ++i) {
    const ParameterRole role = specs[i].role;
    if (role == ParameterRole::kFixed || role == ParameterRole::kPerExperiment) continue;
    names->push_back(specs[i].name);
    values->push_back(fit.values[i]);
    determined->push_back(!fit.undetermined[i]);
  }
  for (const ExperimentValue& v : fit.per_experiment) {
    names->push_back(specs[v.parameter].name + "[" + v.experiment + "]");
    values->push_back(v.value);
    determined->push_back(!v.undetermined);
  }
}

void Coefficients(const LeastSquaresSummary& summary, std::vector<std::string>* names,
                  std::vector<double>* values) {
  for (const EquationSummary& e : summary.equations) {
    for (size_t j = 0; j < e.regressed.size(); ++j) {
      if (!e.regressed[j]) continue;
      if (names != nullptr) names->push_back(e.state + "': " + e.coefficients[j]);
      values->push_back(e.theta(j));
    }
  }
}

}  // namespace

bool BootstrapLeastSquares(const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                           const LeastSquaresOptions& options,
                           const std::vector<RegressionRecord>& records,
                           const LeastSquaresResult& fit, const LeastSquaresSummary& summary,
                           BootstrapSummary* bootstrap, std::string* error) {
  const GroupBootstrapOptions& b = options.bootstrap;
  // The quantities the full fit determines; a replicate must determine them too.
  std::vector<std::string> all_names, names, coefficient_names;
  std::vector<double> full, full_coefficients;
  std::vector<bool> bootstrapped;
  Quantities(specs, fit, &all_names, &full, &bootstrapped);
  for (size_t q = 0; q < all_names.size(); ++q) {
    if (bootstrapped[q]) names.push_back(all_names[q]);
  }
  const bool lasso = options.regression.penalty == Penalty::kLasso;
  if (lasso) Coefficients(summary, &coefficient_names, &full_coefficients);

  // Block of each used sample: position in the concatenation of the records' used samples.
  int total = 0;
  for (const RegressionRecord& record : records) {
    for (int k = 0; k < record.size(); ++k) total += record.use[k];
  }
  if (total < b.blocks) {
    *error = "bootstrap: " + std::to_string(total) + " samples for " + std::to_string(b.blocks) +
             " blocks";
    return false;
  }
  std::vector<std::vector<int>> block(records.size());
  for (size_t r = 0, j = 0; r < records.size(); ++r) {
    block[r].assign(records[r].size(), -1);
    for (int k = 0; k < records[r].size(); ++k) {
      if (records[r].use[k]) block[r][k] = static_cast<int>((j++ * b.blocks) / total);
    }
  }
  std::vector<double> lambdas;
  for (const EquationSummary& e : summary.equations) lambdas.push_back(e.lambda);

  auto replicate = [&](const std::vector<int>& counts, std::vector<double>* values,
                       std::vector<double>* coefficients) {
    LeastSquaresOptions o = options;
    o.bootstrap.runs = 0;
    if (b.hold_lambda && options.regression.penalty != Penalty::kNone) o.equation_lambda = lambdas;
    o.sample_counts.resize(records.size());
    for (size_t r = 0; r < records.size(); ++r) {
      o.sample_counts[r].resize(records[r].size());
      for (int k = 0; k < records[r].size(); ++k) {
        o.sample_counts[r][k] = block[r][k] < 0 ? 1 : counts[block[r][k]];
      }
    }
    std::vector<RegressionRecord> copy = records;
    LeastSquaresResult r;
    LeastSquaresSummary s;
    if (!RunLeastSquares(model, specs, o, &copy, &r, &s)) return false;
    std::vector<std::string> replicate_names;
    std::vector<double> replicate_values;
    std::vector<bool> determined;
    Quantities(specs, r, &replicate_names, &replicate_values, &determined);
    if (replicate_names != all_names) return false;
    for (size_t q = 0; q < all_names.size(); ++q) {
      if (!bootstrapped[q]) continue;
      if (!determined[q]) return false;
      values->push_back(replicate_values[q]);
    }
    if (lasso) {
      Coefficients(s, nullptr, coefficients);
      if (coefficients->size() != coefficient_names.size()) coefficients->clear();
    }
    return true;
  };
  if (!RunGroupBootstrap({b.blocks}, names, coefficient_names, replicate, b, bootstrap, error)) {
    return false;
  }
  bootstrap->resampled = "contiguous sample blocks";
  return true;
}

}  // namespace vesselid
