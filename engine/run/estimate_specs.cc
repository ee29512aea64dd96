#include "engine/run/estimate_specs.h"

namespace vesselid {

std::vector<ParameterSpec> EstimateSpecs(const OutputErrorProblem& solved) {
  const ModelHandle& model = solved.model();
  const std::vector<double> values = solved.ParametersOf(0);
  std::vector<ParameterSpec> specs;
  for (size_t i = 0; i < values.size(); ++i) {
    const Variable* parameter = nullptr;
    for (const Variable& v : solved.variables()) {
      if (v.kind == Variable::Kind::kParameter && v.index == static_cast<int>(i)) parameter = &v;
    }
    ParameterSpec spec;
    spec.name = model.info().parameters[i];
    spec.start = values[i];
    spec.role = parameter->role;
    spec.lower = parameter->lower;
    spec.upper = parameter->upper;
    spec.scale = parameter->scale;
    if (!parameter->free && spec.role != ParameterRole::kPerExperiment) {
      spec.role = ParameterRole::kFixed;
    }
    specs.push_back(spec);
  }
  return specs;
}

StageOptions ReplicateOptions(const StageOptions& options) {
  StageOptions replicate = options;
  replicate.use_global_start = false;
  replicate.compute_uncertainty = false;
  replicate.local.num_threads = 1;
  replicate.local.initial_radius = kNearOptimumRadius;  // from the estimate
  replicate.local.progress = nullptr;
  replicate.global.progress = nullptr;
  return replicate;
}

std::unique_ptr<OutputErrorProblem> SolveReplicate(const OutputErrorProblem& solved,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<ParameterSpec>& specs,
                                                   const OutputErrorOptions& problem_options,
                                                   const StageOptions& options) {
  std::string error;
  std::unique_ptr<OutputErrorProblem> p = OutputErrorProblem::Create(
      &solved.model(), std::move(experiments), specs, problem_options, &error);
  if (p == nullptr || p->variables().size() != solved.variables().size()) return nullptr;
  p->SetValues(solved.Values());
  StageSummary summary;
  if (!RunStage(options, p.get(), &summary)) return nullptr;
  return p;
}

}  // namespace vesselid
