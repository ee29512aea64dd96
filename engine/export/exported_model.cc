#include "engine/export/exported_model.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>

#include "Eigen/Cholesky"
#include "Eigen/Eigenvalues"
#include "engine/base/json_number.h"
#include "engine/base/memory_budget.h"
#include "engine/data/interpolation.h"

namespace vesselid {
namespace {

using nlohmann::json;

constexpr int kFormatVersion = 1;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<ExportedVariable> Variables(const std::vector<std::string>& names,
                                        const std::function<std::string(int)>& unit) {
  std::vector<ExportedVariable> variables;
  for (size_t i = 0; i < names.size(); ++i) {
    variables.push_back({names[i], unit(static_cast<int>(i))});
  }
  return variables;
}

json VariablesToJson(const std::vector<ExportedVariable>& variables) {
  json list = json::array();
  for (const ExportedVariable& v : variables) list.push_back({{"name", v.name}, {"unit", v.unit}});
  return list;
}

std::vector<ExportedVariable> VariablesFromJson(const json& list) {
  std::vector<ExportedVariable> variables;
  for (const json& v : list) variables.push_back({v.at("name"), v.at("unit")});
  return variables;
}

// The largest results.json read: a run's holds its estimates, findings and metrics (the
// traces are CSV files beside it), a few MiB; parsing one takes about twice its size.

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

}  // namespace

std::vector<std::vector<double>> DrawEnsemble(const ExportedModel& model, int members,
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

std::shared_ptr<const ModelHandle> MakeExportedModel(const ModelRegistry& registry,
                                                     const std::string& family,
                                                     const ModelOptions& options,
                                                     ExportedModel* m, std::string* error) {
  std::shared_ptr<const ModelHandle> handle = registry.MakeModel(family, options, error);
  if (handle == nullptr) return nullptr;
  const ModelInfo& info = handle->info();
  m->family = family;
  m->options = options;
  m->model = info.name;
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
  return handle;
}

bool ReadExportedModel(const std::string& out_folder, const ModelRegistry& registry, int members,
                       unsigned seed, ExportedModel* model, std::string* error,
                       RunDocument* document) {
  RunDocument read;
  if (!ReadRunDocument(out_folder, &read, error) ||
      !ExportedModelOf(read, registry, members, seed, model, error)) {
    return false;
  }
  if (document != nullptr) *document = std::move(read);
  return true;
}

bool ExportedModelOf(const RunDocument& d, const ModelRegistry& registry, int members,
                     unsigned seed, ExportedModel* model, std::string* error) {
  const std::string& path = d.path;
  ExportedModel m;
  m.results = path;
  m.family = d.family;
  m.options = d.options;
  const std::shared_ptr<const ModelHandle> handle =
      MakeExportedModel(registry, m.family, m.options, &m, error);
  if (handle == nullptr) {
    *error = path + ": model: " + *error;
    return false;
  }
  const ModelInfo& info = handle->info();
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
  const std::string broken = CovarianceProblem(m.covariance_names, m.covariance);
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

json ExportedModelToJson(const ExportedModel& m) {
  json parameters = json::array();
  for (size_t i = 0; i < m.parameters.size(); ++i) {
    parameters.push_back({{"name", m.parameters[i].name},
                          {"unit", m.parameters[i].unit},
                          {"value", m.values[i]},
                          {"std_error", JsonNumber(m.std_errors[i])}});
  }
  json matrix = json::array();
  for (int r = 0; r < m.covariance.rows(); ++r) {
    json line = json::array();
    for (int c = 0; c < m.covariance.cols(); ++c) line.push_back(m.covariance(r, c));
    matrix.push_back(line);
  }
  json interpolation = json::object();
  for (size_t i = 0; i < m.inputs.size() && i < m.interpolation.size(); ++i) {
    interpolation[m.inputs[i].name] = m.interpolation[i];
  }
  return {{"format", "vesselid-model"},
          {"version", kFormatVersion},
          {"family", m.family},
          {"model", m.model},
          {"options", m.options},
          {"states", VariablesToJson(m.states)},
          {"inputs", VariablesToJson(m.inputs)},
          {"outputs", VariablesToJson(m.outputs)},
          {"parameters", parameters},
          {"covariance", {{"names", m.covariance_names}, {"matrix", matrix}}},
          {"ensemble",
           {{"source", m.ensemble_source}, {"seed", m.ensemble_seed}, {"members", m.ensemble}}},
          {"max_step", m.max_step},
          {"interpolation", interpolation},
          {"results", m.results}};
}

bool ExportedModelFromJson(const json& j, ExportedModel* model, std::string* error) {
  try {
    if (j.at("format") != "vesselid-model" || j.at("version") != kFormatVersion) {
      *error = "not a vesselid model.json of version " + std::to_string(kFormatVersion);
      return false;
    }
    ExportedModel m;
    m.family = j.at("family");
    m.model = j.at("model");
    m.options = j.at("options").get<ModelOptions>();
    m.states = VariablesFromJson(j.at("states"));
    m.inputs = VariablesFromJson(j.at("inputs"));
    m.outputs = VariablesFromJson(j.at("outputs"));
    for (const json& p : j.at("parameters")) {
      m.parameters.push_back({p.at("name"), p.at("unit")});
      m.values.push_back(p.at("value"));
      m.std_errors.push_back(NumberOr(p.at("std_error"), kNaN));
    }
    m.covariance_names = j.at("covariance").at("names").get<std::vector<std::string>>();
    const json& matrix = j.at("covariance").at("matrix");
    const int n = static_cast<int>(m.covariance_names.size());
    m.covariance.resize(n, n);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) m.covariance(r, c) = matrix.at(r).at(c);
    }
    m.ensemble = j.at("ensemble").at("members").get<std::vector<std::vector<double>>>();
    m.ensemble_seed = j.at("ensemble").at("seed");
    m.ensemble_source = j.at("ensemble").value("source", "covariance");
    for (const std::vector<double>& member : m.ensemble) {
      if (member.size() != m.values.size()) {
        *error = "ensemble member of " + std::to_string(member.size()) + " values, expected " +
                 std::to_string(m.values.size());
        return false;
      }
    }
    m.max_step = j.at("max_step");
    const json methods = j.value("interpolation", json::object());
    for (const ExportedVariable& input : m.inputs) {
      Interpolation method = Interpolation::kLinear;
      const std::string text = methods.value(input.name, InterpolationToString(method));
      if (!StringToInterpolation(text, &method)) {
        *error = "interpolation." + input.name + ": unknown method '" + text + "'";
        return false;
      }
      m.interpolation.push_back(text);
    }
    m.results = j.value("results", "");
    *model = std::move(m);
    return true;
  } catch (const json::exception& e) {
    *error = std::string("model.json: ") + e.what();
    return false;
  }
}

}  // namespace vesselid
