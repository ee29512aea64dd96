#include "engine/stage.h"

#include <chrono>
#include <cstdio>

namespace vesselid {
namespace {

// Reports the members of each exchangeable pair in decreasing order (the model is symmetric
// in them, so the swap leaves every simulation unchanged).
void OrderExchangeable(OutputErrorProblem* problem, std::vector<std::string>* notes) {
  const ModelInfo& info = problem->model().info();
  const std::vector<Variable>& variables = problem->variables();
  for (const auto& [first, second] : info.exchangeable) {
    const Variable* a = nullptr;
    const Variable* b = nullptr;
    for (const Variable& v : variables) {
      if (v.kind != Variable::Kind::kParameter || v.experiment >= 0) continue;
      if (v.index == first) a = &v;
      if (v.index == second) b = &v;
    }
    if (a == nullptr || b == nullptr || a->value() >= b->value()) continue;
    const double va = a->value(), vb = b->value();
    if (vb > a->upper || vb < a->lower || va > b->upper || va < b->lower) {
      notes->push_back(a->name + " < " + b->name + " and their bounds forbid the swap");
      continue;
    }
    a->set_value(vb);
    b->set_value(va);
    notes->push_back("swapped " + a->name + " and " + b->name + " so that " + a->name +
                     " >= " + b->name);
  }
}

}  // namespace

bool StageOptions::IsValid(std::string* error) const {
  if (!local.IsValid(error)) return false;
  return !use_global_start || global.IsValid(error);
}

std::string StageSummary::BriefReport() const {
  char text[512];
  if (!usable) {
    std::snprintf(text, sizeof(text), "stage %s failed: %s", name.c_str(), message.c_str());
    return text;
  }
  const LocalSolveSummary& l = local();
  std::snprintf(text, sizeof(text),
                "stage %s: cost %.6e after %d iterations (%s), %zu refinement(s), %.3f s",
                name.c_str(), l.final_cost, l.iterations, l.termination.c_str(),
                refinements.size(), time_seconds);
  return text;
}

bool RunStage(const StageOptions& options, OutputErrorProblem* problem, StageSummary* summary) {
  *summary = StageSummary();
  summary->name = options.name;
  const auto start_time = std::chrono::steady_clock::now();
  if (!options.IsValid(&summary->message)) return false;

  std::vector<std::vector<double>> starts{problem->Values()};
  if (options.use_global_start) {
    if (!RunGlobalStart(options.global, problem, &summary->global)) {
      summary->message = "global start: " + summary->global.message;
      return false;
    }
    for (const std::vector<double>& c : summary->global.candidates) starts.push_back(c);
  }

  std::vector<double> best_values;
  double best_cost = 0.0;
  std::string last_failure;
  for (size_t i = 0; i < starts.size(); ++i) {
    problem->SetValues(starts[i]);
    LocalSolveSummary local;
    RunLocalSolve(options.local, problem, &local);
    summary->refinements.push_back(local);
    if (!local.usable) {
      last_failure = local.message;
      continue;
    }
    if (summary->chosen < 0 || local.final_cost < best_cost) {
      summary->chosen = static_cast<int>(i);
      best_cost = local.final_cost;
      best_values = problem->Values();
    }
  }
  if (summary->chosen < 0) {
    summary->message = "no local refinement succeeded: " + last_failure;
    return false;
  }
  problem->SetValues(best_values);
  OrderExchangeable(problem, &summary->notes);

  if (options.compute_uncertainty &&
      !ComputeUncertainty(problem, best_cost, &summary->uncertainty)) {
    summary->notes.push_back("uncertainty: " + summary->uncertainty.message);
  }
  if (!EvaluateFit(*problem, &summary->fits, &summary->message)) return false;
  summary->usable = true;
  summary->time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return true;
}

}  // namespace vesselid
