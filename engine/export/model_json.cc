#include "engine/export/model_json.h"

#include <limits>

#include "engine/base/json_number.h"
#include "engine/base/nan.h"
#include "engine/data/interpolation.h"

namespace vesselid {
namespace {

using nlohmann::json;

constexpr int kFormatVersion = 1;

json VariablesToJson(const std::vector<ModelVariable>& variables) {
  json list = json::array();
  for (const ModelVariable& v : variables) list.push_back({{"name", v.name}, {"unit", v.unit}});
  return list;
}

std::vector<ModelVariable> VariablesFromJson(const json& list) {
  std::vector<ModelVariable> variables;
  for (const json& v : list) variables.push_back({v.at("name"), v.at("unit")});
  return variables;
}

}  // namespace

json IdentifiedModelToJson(const IdentifiedModel& m) {
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

bool IdentifiedModelFromJson(const json& j, IdentifiedModel* model, std::string* error) {
  try {
    if (j.at("format") != "vesselid-model" || j.at("version") != kFormatVersion) {
      *error = "not a vesselid model.json of version " + std::to_string(kFormatVersion);
      return false;
    }
    IdentifiedModel m;
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
    for (const ModelVariable& input : m.inputs) {
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
