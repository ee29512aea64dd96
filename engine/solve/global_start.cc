#include "engine/solve/global_start.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/solve/multistart.h"
#include "nlopt.hpp"

namespace vesselid {
namespace {

constexpr double kDivergedCost = 1e100;

struct SearchState {
  OutputErrorProblem* problem = nullptr;
  std::vector<int> searched;  // variable indices
  std::vector<double> base;   // values of all variables
  int evaluations = 0;
  int failed = 0;
  const ProgressCallback* progress = nullptr;
  std::vector<double> best_history;  // best finite cost after each evaluation
  // Every visited point, normalised, with its cost.
  std::vector<std::pair<double, std::vector<double>>> visited;
};

double Objective(unsigned n, const double* z, double* gradient, void* data) {
  auto* s = static_cast<SearchState*>(data);
  const std::vector<Variable>& variables = s->problem->variables();
  for (unsigned i = 0; i < n; ++i) {
    const Variable& v = variables[s->searched[i]];
    v.set_value(v.lower + std::clamp(z[i], 0.0, 1.0) * (v.upper - v.lower));
  }
  ++s->evaluations;
  double cost = 0.0;
  if (!s->problem->Cost(&cost) || !std::isfinite(cost)) {
    ++s->failed;
    cost = kDivergedCost;
  }
  s->visited.emplace_back(cost, std::vector<double>(z, z + n));
  double best = s->best_history.empty() ? std::nan("") : s->best_history.back();
  if (cost < kDivergedCost && !(best <= cost)) best = cost;
  s->best_history.push_back(best);
  if (*s->progress) {
    SolveProgress p;
    p.phase = SolveProgress::Phase::kGlobal;
    p.iteration = s->evaluations;
    p.cost = best;
    (*s->progress)(p);
  }
  return cost;
}

}  // namespace

bool GlobalStartOptions::IsValid(std::string* error) const {
  std::string message;  // the algorithm's own options first, then those both kinds share
  if (algorithm == "multistart") {
    if (points < 1) {
      message = "points must be >= 1";
    } else if (short_iterations < 1) {
      message = "short_iterations must be >= 1";
    } else if (threads < 0) {
      message = "threads must be >= 0 (0: the machine's cores)";
    }
  } else if (nlopt_algorithm_from_string(algorithm.c_str()) < 0) {
    message = "unknown algorithm '" + algorithm +
              "': multistart or an NLopt global algorithm (e.g. GN_DIRECT_L, GN_CRS2_LM, "
              "GN_ISRES)";
  } else if (algorithm.rfind("GN_", 0) != 0 && algorithm.rfind("G_MLSL", 0) != 0) {
    message = "algorithm '" + algorithm + "' is not a global derivative-free NLopt algorithm";
  } else if (max_evaluations < 1) {
    message = "max_evaluations must be >= 1";
  }
  if (message.empty()) {
    if (!(max_time_seconds > 0.0)) {
      message = "max_time_seconds must be > 0";
    } else if (candidates < 1) {
      message = "candidates must be >= 1";
    } else if (!(min_separation >= 0.0)) {
      message = "min_separation must be >= 0";
    }
  }
  if (message.empty()) return true;
  *error = message;
  return false;
}

std::string GlobalStartSummary::BriefReport() const {
  if (!run) return "global start: not run";
  char text[256];
  if (algorithm == "multistart") {
    std::snprintf(text, sizeof(text),
                  "global start (multistart): %d points (%d diverged, %d abandoned), %d distinct "
                  "end points, best cost %.6e, %.3f s",
                  evaluations, failed_evaluations, abandoned, clusters, best_cost, time_seconds);
    std::string report = text;
    if (horizon_seconds > 0.0) {
      std::snprintf(text, sizeof(text), "; searched on %.3g s pieces of the experiments",
                    horizon_seconds);
      report += text;
    }
    if (!around_start.empty()) {
      std::string names;
      for (const std::string& n : around_start) names += (names.empty() ? "" : ", ") + n;
      report += "; searched within a factor 3 of their start (one-sided or no bounds): " + names;
    }
    return report;
  }
  std::snprintf(text, sizeof(text),
                "global start: %d evaluations (%d diverged), best cost %.6e, %.3f s, %s",
                evaluations, failed_evaluations, best_cost, time_seconds, result.c_str());
  return text;
}

bool RunGlobalStart(const GlobalStartOptions& options, OutputErrorProblem* problem,
                    GlobalStartSummary* summary) {
  *summary = GlobalStartSummary();
  if (!options.IsValid(&summary->message)) return false;
  if (options.algorithm == "multistart") {
    const bool found = RunMultistart(options, problem, summary);
    summary->algorithm = options.algorithm;
    return found;
  }
  summary->algorithm = options.algorithm;
  const auto start_time = std::chrono::steady_clock::now();
  SearchState state;
  state.problem = problem;
  state.progress = &options.progress;
  state.base = problem->Values();
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    if (variables[i].free && variables[i].bounded()) {
      state.searched.push_back(static_cast<int>(i));
      summary->variables.push_back(variables[i].name);
    }
  }
  if (state.searched.empty()) {
    summary->message = "no free variable has finite lower and upper bounds to search";
    return false;
  }
  const unsigned n = static_cast<unsigned>(state.searched.size());
  std::vector<double> z(n);
  for (unsigned i = 0; i < n; ++i) {
    const Variable& v = variables[state.searched[i]];
    z[i] = (state.base[state.searched[i]] - v.lower) / (v.upper - v.lower);
  }

  nlopt::srand(options.seed);
  nlopt::opt optimizer(options.algorithm.c_str(), n);
  optimizer.set_lower_bounds(std::vector<double>(n, 0.0));
  optimizer.set_upper_bounds(std::vector<double>(n, 1.0));
  optimizer.set_min_objective(Objective, &state);
  optimizer.set_maxeval(options.max_evaluations);
  optimizer.set_maxtime(options.max_time_seconds);
  if (options.population > 0) optimizer.set_population(options.population);
  if (options.algorithm.rfind("G_MLSL", 0) == 0) {
    nlopt::opt local(nlopt::LN_BOBYQA, n);
    local.set_xtol_rel(1e-4);
    local.set_maxeval(std::max(20, options.max_evaluations / 20));
    optimizer.set_local_optimizer(local);
  }
  double best = 0.0;
  try {
    nlopt::result result = optimizer.optimize(z, best);
    summary->result = nlopt_result_to_string(static_cast<nlopt_result>(result));
  } catch (const std::exception& e) {
    // Budget exhaustion and round-off stops still leave usable visited points.
    summary->result = std::string("stopped: ") + e.what();
  }
  summary->run = true;
  summary->evaluations = state.evaluations;
  summary->failed_evaluations = state.failed;
  summary->best_cost_history = std::move(state.best_history);

  // Best distinct visited points.
  std::sort(state.visited.begin(), state.visited.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::vector<double>> chosen;
  for (const auto& [cost, point] : state.visited) {
    if (cost >= kDivergedCost) break;
    bool distinct = true;
    for (const std::vector<double>& c : chosen) {
      double distance = 0.0;
      for (unsigned i = 0; i < n; ++i) distance = std::max(distance, std::abs(c[i] - point[i]));
      distinct = distinct && distance >= options.min_separation;
    }
    if (!distinct) continue;
    chosen.push_back(point);
    std::vector<double> values = state.base;
    for (unsigned i = 0; i < n; ++i) {
      const Variable& v = variables[state.searched[i]];
      values[state.searched[i]] = v.lower + std::clamp(point[i], 0.0, 1.0) * (v.upper - v.lower);
    }
    summary->candidates.push_back(values);
    summary->candidate_costs.push_back(cost);
    if (static_cast<int>(chosen.size()) == options.candidates) break;
  }
  problem->SetValues(state.base);
  summary->best_cost = summary->candidate_costs.empty() ? -1.0 : summary->candidate_costs[0];
  summary->time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  if (summary->candidates.empty()) {
    summary->message = "every simulation in the global search diverged";
    return false;
  }
  return true;
}

}  // namespace vesselid
