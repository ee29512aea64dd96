#include "engine/run/held_out.h"

namespace vesselid {

std::unique_ptr<OutputErrorProblem> HeldOutProblem(const ModelHandle& model,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<std::string>& free_states,
                                                   const LocalSolveOptions& local,
                                                   const std::vector<double>& values,
                                                   std::string* error) {
  std::vector<ParameterSpec> fixed;
  for (size_t i = 0; i < values.size(); ++i) {
    ParameterSpec spec;
    spec.name = model.info().parameters[i];
    spec.start = values[i];
    spec.role = ParameterRole::kFixed;
    fixed.push_back(spec);
  }
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = free_states;
  auto problem =
      OutputErrorProblem::Create(&model, std::move(experiments), fixed, problem_options, error);
  if (problem == nullptr) return nullptr;
  if (problem->num_free() > 0) {
    LocalSolveSummary summary;
    if (!RunLocalSolve(local, problem.get(), &summary)) {
      *error = "initial-state estimate: " + summary.message;
      return nullptr;
    }
  }
  return problem;
}

bool SimulateHeldOut(const RunConfig& config, const ModelHandle& model,
                     const std::vector<std::string>& names, const ExperimentOptions& options,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, TrajectoryCache* cache,
                     std::vector<ExperimentFit>* fits, std::string* error) {
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, names, model, options, cache, &experiments, error)) {
    return false;
  }
  const std::unique_ptr<OutputErrorProblem> problem =
      HeldOutProblem(model, std::move(experiments), free_states, local, values, error);
  return problem != nullptr && EvaluateFit(*problem, fits, error);
}

}  // namespace vesselid
