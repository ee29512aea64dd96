#include "engine/output/identified_model.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "Eigen/Cholesky"
#include "Eigen/Eigenvalues"
#include "engine/base/memory_budget.h"
#include "engine/base/nan.h"
#include "engine/data/interpolation.h"
#include "engine/run/display_units.h"

namespace vesselid {
namespace {


std::vector<ModelVariable> Variables(const std::vector<std::string>& names,
                                     const std::function<std::string(int)>& unit) {
  std::vector<ModelVariable> variables;
  for (size_t i = 0; i < names.size(); ++i) {
    variables.push_back({names[i], unit(static_cast<int>(i))});
  }
  return variables;
}

// Bytes an ensemble of `members` draws of `n` parameters takes: the vectors, and the
// model.json text and document an export makes of them.
double EnsembleBytes(double members, int n) { return members * (n * (8.0 + 16.0 + 25.0) + 96.0); }

// "" when `covariance` (of `names`) is finite, symmetric and positive semi-definite; else
// which parameter breaks it and how.
std::string CovarianceProblem(const std::vector<std::string>& names,
                              const Eigen::MatrixXd& covariance) {
  const int n = static_cast<int>(names.size());
  for (int a = 0; a < n; ++a) {
    if (!(std::isfinite(covariance(a, a)) && covariance(a, a) >= 0.0)) {
      return "the variance of " + names[a] + " is not a finite number (its std_error)";
    }
    for (int b = 0; b < n; ++b) {
      const double c = covariance(a, b), scale = std::sqrt(covariance(a, a) * covariance(b, b));
      if (!std::isfinite(c) || std::abs(c) > scale * (1.0 + 1e-9) ||
          std::abs(c - covariance(b, a)) > 1e-9 * scale) {
        return "the correlation of " + names[a] + " and " + names[b] +
               " is not a correlation (finite, symmetric, within [-1, 1])";
      }
    }
  }
  if (n == 0) return "";
  // Positive semi-definite up to rounding: the correlation matrix's eigenvalues >= -1e-8.
  Eigen::VectorXd sd = covariance.diagonal().cwiseSqrt();
  for (int a = 0; a < n; ++a) sd(a) = sd(a) > 0.0 ? 1.0 / sd(a) : 0.0;
  const Eigen::MatrixXd correlation = sd.asDiagonal() * covariance * sd.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(correlation);
  if (eigen.eigenvalues().minCoeff() < -1e-8) {
    Eigen::Index worst = 0;
    eigen.eigenvectors().col(0).cwiseAbs().maxCoeff(&worst);
    return "the correlations are not those of any covariance (not positive semi-definite; "
           "most in " + names[worst] + ")";
  }
  return "";
}

// The model the run's final values belong to: the last stage's own restriction, else the
// run's (what results.json names as the last model stage's model_options).
std::shared_ptr<const ModelHandle> FinalModel(const RunConfig& config, const RunResult& result) {
  if (!result.stages.empty()) {
    for (const StageConfig& stage : config.stages) {
      if (stage.options.name == result.stages.back().name && stage.model) return stage.model;
    }
  }
  return config.model;
}

}  // namespace

std::vector<std::vector<double>> DrawEnsemble(const IdentifiedModel& model, int members,
                                              unsigned seed) {
  const int n = static_cast<int>(model.covariance_names.size());
  std::vector<int> index(n);
  for (int i = 0; i < n; ++i) {
    for (size_t k = 0; k < model.parameters.size(); ++k) {
      if (model.parameters[k].name == model.covariance_names[i]) index[i] = static_cast<int>(k);
    }
  }
  // C = L D L^T; a draw is values + L sqrt(max(D, 0)) z (a semidefinite covariance, e.g. an
  // undetermined direction of zero variance, keeps its zero directions).
  Eigen::LDLT<Eigen::MatrixXd> ldlt(model.covariance);
  Eigen::MatrixXd factor = Eigen::MatrixXd::Zero(n, n);
  if (n > 0) {
    const Eigen::VectorXd d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
    const Eigen::MatrixXd l = ldlt.matrixL();
    factor = ldlt.transpositionsP().transpose() * (l * d.asDiagonal());
  }
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> ensemble;
  for (int m = 0; m < members; ++m) {
    Eigen::VectorXd z(n);
    for (int i = 0; i < n; ++i) z[i] = normal(random);
    const Eigen::VectorXd offset = factor * z;
    std::vector<double> member = model.values;
    for (int i = 0; i < n; ++i) member[index[i]] += offset[i];
    ensemble.push_back(std::move(member));
  }
  return ensemble;
}

void DescribeModel(std::shared_ptr<const ModelHandle> handle, const std::string& family,
                   const ModelOptions& options, IdentifiedModel* m) {
  const ModelInfo& info = handle->info();
  m->family = family;
  m->options = options;
  m->model = info.name;
  m->handle = std::move(handle);
  m->states = Variables(info.states, [&](int i) { return info.StateUnit(i); });
  m->inputs = Variables(info.inputs, [&](int i) { return info.InputUnit(i); });
  m->outputs = Variables(info.outputs, [&](int i) { return info.OutputUnit(i); });
  m->parameters = Variables(info.parameters, [&](int i) { return info.ParameterUnit(i); });
  m->values = info.parameter_defaults;
  m->interpolation.assign(info.inputs.size(), InterpolationToString(Interpolation::kLinear));
  m->std_errors.assign(info.parameters.size(), kNaN);
  m->covariance_names.clear();
  m->covariance.resize(0, 0);
  m->ensemble.clear();
}

bool IdentifiedModelOf(const RunDocument& d, std::shared_ptr<const ModelHandle> handle,
                       int members, unsigned seed, IdentifiedModel* model, std::string* error) {
  const std::string& path = d.path;
  IdentifiedModel m;
  DescribeModel(std::move(handle), d.family, d.options, &m);
  m.results = path;
  const ModelInfo& info = m.handle->info();
  std::map<std::string, int> index;
  for (size_t i = 0; i < info.parameters.size(); ++i) index[info.parameters[i]] = static_cast<int>(i);
  for (const RunDocument::Parameter& p : d.parameters) {
    const auto found = index.find(p.name);
    if (found == index.end()) continue;  // a per-experiment value, an initial state
    if (std::isnan(p.value)) {
      *error = path + ": not the results.json of a finished `vesselid run` (parameters: " +
               p.name + " has no value)";
      return false;
    }
    // A parameter estimated per experiment (a run's rudder bias) takes the training runs'
    // mean, as every other use of the results does (run_result.h, FinalParameter).
    m.values[found->second] = p.value;
    if (p.role == "free") m.std_errors[found->second] = p.std_error;
  }
  // The correlation of the last stage that has one, over the parameters with final SEs.
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    if (std::isfinite(m.std_errors[i])) m.covariance_names.push_back(info.parameters[i]);
  }
  const int n = static_cast<int>(m.covariance_names.size());
  m.covariance = Eigen::MatrixXd::Zero(n, n);
  std::map<std::string, int> row;
  for (size_t r = 0; r < d.correlation_names.size(); ++r) row[d.correlation_names[r]] = static_cast<int>(r);
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    if (m.std_errors[i] < 0.0) {
      *error = path + ": parameters: the std_error of " + info.parameters[i] + " is negative";
      return false;
    }
  }
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double sa = m.std_errors[index[m.covariance_names[a]]];
      const double sb = m.std_errors[index[m.covariance_names[b]]];
      double r = a == b ? 1.0 : 0.0;
      const auto ra = row.find(m.covariance_names[a]), rb = row.find(m.covariance_names[b]);
      if (a != b && ra != row.end() && rb != row.end()) {
        const double listed = d.correlation(ra->second, rb->second);
        r = std::isnan(listed) ? 0.0 : listed;
      }
      m.covariance(a, b) = r * sa * sb;
    }
  }
  // The covariance as the run found it; an ensemble is drawn only from a proper one.
  const std::string broken =
      members > 0 ? CovarianceProblem(m.covariance_names, m.covariance) : std::string();
  if (!broken.empty()) {
    *error = path + ": parameters and stages' correlation: " + broken +
             "; no ensemble can be drawn from it";
    return false;
  }
  const double need = EnsembleBytes(members, static_cast<int>(info.parameters.size()));
  if (need > static_cast<double>(MemoryBudget())) {
    *error = "--members " + std::to_string(members) + ": the ensemble's draws need " +
             FormatBytes(need) + ", more than the memory budget of " +
             FormatBytes(static_cast<double>(MemoryBudget())) +
             " (half this machine's memory); ask for fewer members";
    return false;
  }
  if (d.has_model_stage) {
    m.max_step = std::isnan(d.integration_step) ? 0.0 : d.integration_step;
    if (!(m.max_step > 0.0)) m.max_step = std::isnan(d.max_step) ? 0.0 : d.max_step;
    for (size_t i = 0; i < m.inputs.size(); ++i) {
      const auto method = d.interpolation.find(m.inputs[i].name);
      if (method != d.interpolation.end()) m.interpolation[i] = method->second;
    }
    // As the run listed it: predict flies what is usable and says what it is not.
    m.process_noise = d.process_noise;
  }
  m.ensemble_seed = seed;
  if (!d.replicate_values.empty()) {
    // The bootstrap's replicates (the first `members`), each a full parameter vector.
    m.ensemble_source = "bootstrap";
    for (const std::vector<double>& values : d.replicate_values) {
      if (static_cast<int>(m.ensemble.size()) == members) break;
      std::vector<double> member = m.values;
      for (size_t k = 0; k < d.replicate_names.size() && k < values.size(); ++k) {
        const auto found = index.find(d.replicate_names[k]);
        if (found != index.end()) member[found->second] = values[k];
      }
      m.ensemble.push_back(std::move(member));
    }
  } else {
    m.ensemble = DrawEnsemble(m, members, seed);
  }
  *model = std::move(m);
  return true;
}

bool IdentifiedModelOf(const RunConfig& config, const RunResult& result, int members,
                       unsigned seed, IdentifiedModel* model, std::string* error) {
  if (!IdentifiedModelOf(RunDocumentOf(config, result), FinalModel(config, result), members,
                         seed, model, error)) {
    return false;
  }
  model->degree_names = DegreeChannels(config);
  return true;
}

}  // namespace vesselid
