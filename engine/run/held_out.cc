#include "engine/run/held_out.h"

#include <cstdio>
#include <map>

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
  // One problem per experiment (they share nothing with the parameters fixed), so that one
  // that diverges is recorded and the others are still measured.
  fits->clear();
  for (Experiment& experiment : experiments) {
    ExperimentFit fit;
    fit.experiment = experiment.name;
    std::vector<Experiment> one;
    one.push_back(std::move(experiment));
    std::string why;
    const std::unique_ptr<OutputErrorProblem> problem =
        HeldOutProblem(model, std::move(one), free_states, local, values, &why);
    std::vector<ExperimentFit> evaluated;
    if (problem == nullptr) {
      fit.diverged = true;
      fit.message = why;
    } else {
      EvaluateFit(*problem, &evaluated, &why);  // a divergence is recorded in the fit
      fit = std::move(evaluated.front());
    }
    fits->push_back(std::move(fit));
  }
  return true;
}

namespace {

// Per output: MAE pooled over the runs that did not diverge; the number that did.
void Pool(const std::vector<ExperimentFit>& fits, std::map<std::string, double>* mae,
          int* diverged) {
  std::map<std::string, std::pair<double, int>> sums;
  *diverged = 0;
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) {
      ++*diverged;
      continue;
    }
    for (const ChannelMetrics& c : fit.channels) {
      sums[c.output].first += c.mae * c.samples;
      sums[c.output].second += c.samples;
    }
  }
  for (const auto& [output, sum] : sums) {
    if (sum.second > 0) (*mae)[output] = sum.first / sum.second;
  }
}

}  // namespace

HeldOutCheck CompareHeldOut(const std::vector<ExperimentFit>& start,
                            const std::vector<ExperimentFit>& stage) {
  HeldOutCheck check;
  check.done = true;
  std::map<std::string, double> start_mae, stage_mae;
  Pool(start, &start_mae, &check.start_diverged);
  Pool(stage, &stage_mae, &check.stage_diverged);
  double ratio_sum = 0.0;
  int ratios = 0;
  for (const auto& [output, mae] : stage_mae) {
    auto before = start_mae.find(output);
    if (before == start_mae.end()) continue;
    check.outputs.push_back(output);
    check.start_mae.push_back(before->second);
    check.stage_mae.push_back(mae);
    if (before->second > 0.0) {
      ratio_sum += mae / before->second;
      ++ratios;
    }
  }
  check.worse = check.stage_diverged > check.start_diverged ||
                (check.stage_diverged == check.start_diverged && ratios > 0 &&
                 ratio_sum / ratios > kHeldOutTolerance);
  return check;
}

std::string DescribeHeldOut(const HeldOutCheck& check) {
  std::string text;
  if (check.stage_diverged > check.start_diverged) {
    text = std::to_string(check.stage_diverged) + " held-out run(s) diverge (" +
           std::to_string(check.start_diverged) + " at its start)";
  }
  for (size_t i = 0; i < check.outputs.size(); ++i) {
    char item[128];
    std::snprintf(item, sizeof(item), "%s %.4g -> %.4g", check.outputs[i].c_str(),
                  check.start_mae[i], check.stage_mae[i]);
    text += (text.empty() ? "held-out MAE "
             : i == 0     ? "; held-out MAE "
                          : ", ") +
            std::string(item);
  }
  return text;
}

}  // namespace vesselid
