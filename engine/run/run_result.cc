#include "engine/run/run_result.h"

namespace vesselid {

const char* EstimateKindToString(EstimateKind kind) {
  switch (kind) {
    case EstimateKind::kInitialState:
      return "initial_state";
    case EstimateKind::kNoise:
      return "noise";
    case EstimateKind::kParameter:
      break;
  }
  return "parameter";
}

bool StringToEstimateKind(const std::string& text, EstimateKind* kind) {
  for (EstimateKind k : {EstimateKind::kParameter, EstimateKind::kInitialState,
                         EstimateKind::kNoise}) {
    if (text == EstimateKindToString(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::vector<double> StageParameterValues(const ModelInfo& info, const StageResult& stage) {
  // Per-experiment estimates are named "<parameter>[<experiment>]".
  auto base_name = [](const std::string& name) { return name.substr(0, name.find('[')); };
  std::vector<double> values;
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    double sum = 0.0;
    int count = 0;
    for (const Estimate& e : stage.estimates) {
      if (e.kind != EstimateKind::kParameter || base_name(e.name) != info.parameters[i]) continue;
      sum += e.value;
      ++count;
      if (e.experiment.empty()) break;
    }
    values.push_back(count > 0 ? sum / count : info.parameter_defaults[i]);
  }
  return values;
}

Estimate ParameterEstimate(const ParameterSpec& spec, double value, double std_error) {
  Estimate e;
  e.name = spec.name;
  e.kind = EstimateKind::kParameter;
  e.role = spec.role;
  e.value = value;
  e.start = spec.start;
  e.std_error = std_error;
  e.lower = spec.lower;
  e.upper = spec.upper;
  return e;
}

}  // namespace vesselid
