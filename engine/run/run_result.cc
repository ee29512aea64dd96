#include "engine/run/run_result.h"

namespace vesselid {

const char* EstimateKindToString(EstimateKind kind) {
  return kind == EstimateKind::kInitialState ? "initial_state" : "parameter";
}

bool StringToEstimateKind(const std::string& text, EstimateKind* kind) {
  for (EstimateKind k : {EstimateKind::kParameter, EstimateKind::kInitialState}) {
    if (text == EstimateKindToString(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::vector<double> StageParameterValues(const ModelInfo& info, const StageResult& stage) {
  std::vector<double> values;
  for (const std::string& name : info.parameters) {
    for (const Estimate& e : stage.estimates) {
      if (e.kind == EstimateKind::kParameter && e.name == name) {
        values.push_back(e.value);
        break;
      }
    }
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
