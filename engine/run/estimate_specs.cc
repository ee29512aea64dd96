#include "engine/run/estimate_specs.h"

#include <algorithm>
#include <map>

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

std::unique_ptr<OutputErrorProblem> RefineFromEstimate(const OutputErrorProblem& solved,
                                                       std::vector<Experiment> experiments,
                                                       const OutputErrorOptions& problem_options,
                                                       StageOptions options,
                                                       StageSummary* summary, std::string* error) {
  std::unique_ptr<OutputErrorProblem> refined = OutputErrorProblem::Create(
      &solved.model(), std::move(experiments), EstimateSpecs(solved), problem_options, error);
  if (refined == nullptr) return nullptr;
  std::map<std::string, double> by_name;
  for (const Variable& v : solved.variables()) by_name[v.name] = v.value();
  for (const Variable& v : refined->variables()) {
    auto found = by_name.find(v.name);
    if (found != by_name.end()) v.set_value(std::clamp(found->second, v.lower, v.upper));
  }
  options.use_global_start = false;
  options.local.initial_radius = kNearOptimumRadius;  // from the solved estimate
  StageSummary again;
  if (!RunStage(options, refined.get(), &again)) {
    *error = again.message;
    return nullptr;
  }
  again.notes.insert(again.notes.begin(), summary->notes.begin(), summary->notes.end());
  // What the earlier solves found about the process stays; what they found about their own
  // estimate (its intervals) the new solve finds again for its own.
  for (const Finding& f : summary->findings) {
    if (f.kind != FindingKind::kNarrowIntervals) again.findings.push_back(f);
  }
  again.name = summary->name;
  *summary = std::move(again);
  return refined;
}

}  // namespace vesselid
