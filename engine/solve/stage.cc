#include "engine/solve/stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "engine/solve/search_box.h"

namespace vesselid {
namespace {

// Shared free variables of each exchangeable pair.
std::vector<std::pair<const Variable*, const Variable*>> ExchangeablePairs(
    const OutputErrorProblem& problem) {
  std::vector<std::pair<const Variable*, const Variable*>> pairs;
  for (const auto& [first, second] : problem.model().info().exchangeable) {
    const Variable* a = nullptr;
    const Variable* b = nullptr;
    for (const Variable& v : problem.variables()) {
      if (v.kind != Variable::Kind::kParameter || v.experiment >= 0 || !v.free) continue;
      if (v.index == first) a = &v;
      if (v.index == second) b = &v;
    }
    if (a != nullptr && b != nullptr) pairs.emplace_back(a, b);
  }
  return pairs;
}

// Reports the members of each exchangeable pair in decreasing order (the model is symmetric
// in them, so the swap leaves every simulation unchanged).
void OrderExchangeable(OutputErrorProblem* problem, std::vector<std::string>* notes) {
  for (const auto& [a, b] : ExchangeablePairs(*problem)) {
    const double va = a->value(), vb = b->value();
    if (va >= vb) continue;
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

// A model symmetric in (a, b) has zero gradient across a = b, so a local solve that reaches
// the ridge stays there. If it ended on it, restart with the pair split by each of
// kRidgeSplits either way of its geometric mean (the true pair may be an order of magnitude
// apart, e.g. Nomoto T1/T2 ~ 7) and keep the best.
constexpr double kRidgeSplits[] = {1.5, 4.0, 12.0};
constexpr double kRidgeGain = 1e-9;  // relative cost decrease that counts as leaving it

bool OnRidge(double a, double b) {
  return std::abs(a - b) <= 1e-3 * std::max(std::abs(a), std::abs(b));
}

// A candidate's refinement joins an earlier optimum within kJoinDistance (the search box's
// max-norm coordinates: 5 % of each linear range, 0.05 of the decades of a log range; the
// multistart's default cluster distance) at a cost no lower by kJoinSameCost (relative).
constexpr double kJoinDistance = 0.05;
constexpr double kJoinSameCost = 1e-6;

void EscapeExchangeRidge(const LocalSolveOptions& options, OutputErrorProblem* problem,
                         LocalSolveSummary* local, std::vector<std::string>* notes) {
  for (const auto& [a, b] : ExchangeablePairs(*problem)) {
    const double va = a->value(), vb = b->value();
    if (!OnRidge(va, vb)) continue;
    const std::vector<double> ridge = problem->Values();
    const double mean = std::copysign(std::sqrt(std::abs(va * vb)), va);
    std::vector<double> best_values;
    LocalSolveSummary best = *local;
    for (double split : kRidgeSplits) {
      problem->SetValues(ridge);
      a->set_value(std::clamp(mean * split, a->lower, a->upper));
      b->set_value(std::clamp(mean / split, b->lower, b->upper));
      LocalSolveSummary attempt;
      // Left only where the split reached a lower cost off the ridge.
      if (RunLocalSolve(options, problem, &attempt) &&
          attempt.final_cost < best.final_cost - kRidgeGain * local->final_cost &&
          !OnRidge(a->value(), b->value())) {
        best = attempt;
        best_values = problem->Values();
      }
    }
    if (best_values.empty()) {
      problem->SetValues(ridge);
      notes->push_back("ended on the " + a->name + " = " + b->name +
                       " ridge: starts split either way of it found no lower cost, so the "
                       "data do not tell the two apart here");
      continue;
    }
    char text[256];
    std::snprintf(text, sizeof(text), "left the %s = %s ridge (cost %.6e -> %.6e)",
                  a->name.c_str(), b->name.c_str(), local->final_cost, best.final_cost);
    notes->push_back(text);
    best.initial_cost = local->initial_cost;
    best.iterations += local->iterations;
    best.cost_history.insert(best.cost_history.begin(), local->cost_history.begin(),
                             local->cost_history.end());
    best.time_seconds += local->time_seconds;
    *local = best;
    problem->SetValues(best_values);
  }
}

// The filter-error method's solve runs on offsets centred at its start (filter_error_cost.h):
// from the floor's, the Gauss-Newton curvature of log S is too low by log(S / floor), and a
// fit crawled for 30 iterations through the last thousandth of -log L, or stalled on a plateau
// a third of a standard error from its optimum. The centred offsets leave the variances room
// to fall by e^(1 + kSolveOffsetMargin); a solve whose variances come within kRecentreBelow of
// that (the log-variance rows are clamped beyond it, their gradient lost) pauses and goes on
// re-centred, at most kMaxRecentredSolves times. Costs are reported under the floor's offsets,
// so that refinements compare on one scale: the two differ by a constant per solve.
constexpr double kSolveOffsetMargin = 1.0;
constexpr double kRecentreBelow = 0.25;
constexpr int kMaxRecentredSolves = 12;

// The floor's cost minus the centred one at the current values (a constant of the solve).
double OffsetShift(const std::vector<double>& floor_offsets, OutputErrorProblem* problem) {
  const std::vector<double> centred = problem->CentreLikelihood();  // the current ones
  problem->RestoreOffsets(centred);
  double on_centred = 0.0, on_floor = 0.0;
  const bool ok = problem->Cost(&on_centred);
  problem->RestoreOffsets(floor_offsets);
  const bool ok_floor = problem->Cost(&on_floor);
  problem->RestoreOffsets(centred);
  return ok && ok_floor ? on_floor - on_centred : 0.0;
}

// Adds a paused or final pass to the refinement's summary, its costs shifted by `shift`.
void AddPass(const LocalSolveSummary& pass, double shift, bool first, LocalSolveSummary* local) {
  if (first) {
    *local = pass;
    for (double& c : local->cost_history) c += shift;
    local->final_cost += shift;
    return;
  }
  // The pass starts where the last ended: its history's first entry is that point again.
  for (size_t k = 1; k < pass.cost_history.size(); ++k) {
    local->cost_history.push_back(pass.cost_history[k] + shift);
  }
  local->iterations += pass.iterations;
  local->successful_steps += pass.successful_steps;
  local->unsuccessful_steps += pass.unsuccessful_steps;
  local->time_seconds += pass.time_seconds;
  local->residual_seconds += pass.residual_seconds;
  local->jacobian_seconds += pass.jacobian_seconds;
  local->linear_solver_seconds += pass.linear_solver_seconds;
  local->residual_evaluations += pass.residual_evaluations;
  local->jacobian_evaluations += pass.jacobian_evaluations;
  local->usable = pass.usable;
  local->termination = pass.termination;
  local->message = pass.message;
  local->final_cost = pass.final_cost + shift;
}

// `shift`: set before each pass to the floor's cost minus the centred one, for the callers'
// comparisons of the costs the solve reports with costs on the floor's offsets. Returns
// RunLocalSolve's answer for the last pass.
bool RunCentredSolve(const LocalSolveOptions& options, OutputErrorProblem* problem,
                     LocalSolveSummary* local, double* shift) {
  double start_cost = 0.0;
  const bool started = problem->Cost(&start_cost);
  const std::vector<double> floor_offsets = problem->CentreLikelihood(kSolveOffsetMargin);
  bool paused = false;
  LocalSolveOptions pausing = options;
  pausing.keep_going = [&](int iteration, double cost) {
    if (problem->LowestLikelihoodTerm() < kRecentreBelow) {
      paused = true;
      return false;
    }
    return !options.keep_going || options.keep_going(iteration, cost);
  };
  bool ran = false;
  for (int pass = 0; pass <= kMaxRecentredSolves; ++pass) {
    if (pass > 0) problem->CentreLikelihood(kSolveOffsetMargin);
    *shift = OffsetShift(floor_offsets, problem);
    paused = false;
    LocalSolveSummary one;
    ran = RunLocalSolve(pass < kMaxRecentredSolves ? pausing : options, problem, &one);
    if (paused) {
      // Abandoned at an accepted iterate (the problem holds it): its cost, and on.
      double cost = 0.0;
      one.usable = problem->Cost(&cost);
      one.final_cost = cost;
      one.termination = "PAUSED";
    }
    AddPass(one, *shift, pass == 0, local);
    if (!paused || !one.usable) break;
  }
  problem->RestoreOffsets(floor_offsets);
  *shift = 0.0;
  if (started && local->run) local->initial_cost = start_cost;
  return ran || local->usable;
}

// Solves for the free initial states with every free parameter held constant, where the
// problem holds segments (pieces of longer records, started from zero velocities). Whole
// records start from the data's own guesses: held at far parameter starts (a rudder bias at
// 0, a time constant 5x off), the states would absorb what the parameters do not explain,
// and a second-order Nomoto fit then follows its pole-zero cancellation (T2 = T3), where
// such states are unobservable, instead of its optimum (tests/benchmarks/peer/tanker4_*).
void SolveInitialStates(const LocalSolveOptions& options, OutputErrorProblem* problem) {
  bool segments = false;
  for (const Experiment& e : problem->experiments()) segments = segments || e.segment;
  if (!segments) return;
  std::vector<const Variable*> held;
  bool any_state = false;
  for (const Variable& v : problem->variables()) {
    if (!v.free) continue;
    if (v.kind == Variable::Kind::kInitialState) {
      any_state = true;
    } else {
      held.push_back(&v);
    }
  }
  if (!any_state || held.empty()) return;
  for (const Variable* v : held) problem->problem()->SetParameterBlockConstant(v->block);
  LocalSolveOptions quiet = options;
  quiet.progress = nullptr;  // a preliminary solve: the stage reports its refinements
  LocalSolveSummary ignored;
  RunLocalSolve(quiet, problem, &ignored);
  for (const Variable* v : held) problem->problem()->SetParameterBlockVariable(v->block);
}

// Which refinement won, against the plain local solve from the start point (refinement 0),
// and how many global points diverged.
void NoteGlobalOutcome(const StageSummary& summary, size_t extra_starts,
                       std::vector<std::string>* notes, std::vector<Finding>* findings) {
  const GlobalStartSummary& g = summary.global;
  if (!g.run) return;
  char text[512];
  if (g.failed_evaluations > 0) {
    std::snprintf(text, sizeof(text),
                  "global start: %d of %d %s diverged (simulation not finite) and were left out",
                  g.failed_evaluations, g.evaluations,
                  g.algorithm == "multistart" ? "points" : "evaluations");
    Finding diverged = MakeFinding(FindingKind::kGlobalStartDiverged, text);
    diverged.value = g.failed_evaluations;
    diverged.count = 1;
    findings->push_back(std::move(diverged));
  }
  const LocalSolveSummary& plain = summary.refinements[0];
  const int first_candidate = 1 + static_cast<int>(extra_starts);
  std::string winner = "the plain local solve from the start point";
  if (summary.chosen >= first_candidate) {
    winner = "global candidate " + std::to_string(summary.chosen - first_candidate + 1) + " of " +
             std::to_string(g.candidates.size());
  } else if (summary.chosen > 0) {
    winner = "extra start " + std::to_string(summary.chosen);
  }
  std::string search;
  if (g.algorithm == "multistart") {
    std::snprintf(text, sizeof(text),
                  "%d points screened (%d diverged), %d short solves (%d abandoned, %d "
                  "iterations), %d distinct end points (%d at an optimum already refined)",
                  g.evaluations, g.failed_evaluations, g.short_solves, g.abandoned,
                  g.short_iterations_total, g.clusters, g.known_joined);
  } else {
    std::snprintf(text, sizeof(text), "%d evaluations (%d diverged)", g.evaluations,
                  g.failed_evaluations);
  }
  search = text;
  char plain_cost[64] = "failed";
  if (plain.usable) std::snprintf(plain_cost, sizeof(plain_cost), "%.6e", plain.final_cost);
  std::snprintf(text, sizeof(text),
                "global start (%s, %s): %s won with cost %.6e (plain local solve from the start "
                "point: %s)",
                g.algorithm.c_str(), search.c_str(), winner.c_str(), summary.local().final_cost,
                plain_cost);
  notes->push_back(text);
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
                name.c_str(), l.final_cost, l.iterations, l.termination.c_str(), refinements.size(),
                time_seconds);
  return text;
}

bool RunStage(const StageOptions& options, OutputErrorProblem* problem, StageSummary* summary,
              const std::vector<std::vector<double>>& extra_starts) {
  *summary = StageSummary();
  summary->name = options.name;
  const auto start_time = std::chrono::steady_clock::now();
  if (!options.IsValid(&summary->message)) return false;
  // The disturbance's parameters start decades from where the likelihood wants them (a process
  // noise's spectral density is known to no one beforehand); a scan in decades puts them there.
  if (problem->filter_error()) problem->ScanNoiseStarts();

  std::vector<std::vector<double>> starts{problem->Values()};
  starts.insert(starts.end(), extra_starts.begin(), extra_starts.end());
  const size_t first_candidate = starts.size();
  const SearchBox box(*problem);

  std::vector<double> best_values;
  double best_cost = 0.0;
  std::string last_failure;
  std::vector<std::string> ridge_notes, chosen_ridge_notes;  // of the refinement kept
  // End points of the usable refinements so far and their costs.
  std::vector<std::vector<double>> optima;
  std::vector<double> optimum_costs;
  std::vector<int> optimum_refinement;
  double centred_shift = 0.0;  // RunCentredSolve's, while a filter-error solve runs
  auto refine = [&](size_t i) {
    problem->SetValues(starts[i]);
    if (options.initial_states_first) SolveInitialStates(options.local, problem);
    LocalSolveOptions local_options = options.local;
    if (options.local.progress) {
      local_options.progress = [&options, i, &starts](SolveProgress p) {
        p.refinement = static_cast<int>(i);
        p.refinements = static_cast<int>(starts.size());
        options.local.progress(p);
      };
    }
    // A candidate's refinement stops once it comes close to an optimum already refined at
    // no lower cost: it would end there.
    int joined = -1;
    if (i >= first_candidate && !optima.empty() && box.dimension() > 0) {
      local_options.keep_going = [&](int, double cost) {
        const std::vector<double> now = problem->Values();
        for (size_t k = 0; k < optima.size() && joined < 0; ++k) {
          if (cost + centred_shift >= (1.0 - kJoinSameCost) * optimum_costs[k] &&
              box.Distance(now, optima[k]) < kJoinDistance) {
            joined = optimum_refinement[k];
          }
        }
        return joined < 0;
      };
    }
    LocalSolveSummary local;
    ridge_notes.clear();
    // The multistart searched the ordered half of exchangeable pairs already: a candidate of
    // it that ends on their ridge is not split again (other candidates lie off it).
    const bool escape = i < first_candidate || summary->global.algorithm != "multistart";
    if (problem->filter_error()) {
      if (RunCentredSolve(local_options, problem, &local, &centred_shift) && escape) {
        EscapeExchangeRidge(local_options, problem, &local, &ridge_notes);
      }
    } else if (RunLocalSolve(local_options, problem, &local) && escape) {
      EscapeExchangeRidge(local_options, problem, &local, &ridge_notes);
    }
    if (joined >= 0) {
      local.termination = "JOINED";
      local.message = "stopped near the optimum of refinement " + std::to_string(joined);
    }
    summary->refinements.push_back(local);
    if (!local.usable) {
      if (joined < 0) last_failure = local.message;
      return;
    }
    optima.push_back(problem->Values());
    optimum_costs.push_back(local.final_cost);
    optimum_refinement.push_back(static_cast<int>(i));
    if (summary->chosen < 0 || local.final_cost < best_cost) {
      summary->chosen = static_cast<int>(i);
      best_cost = local.final_cost;
      best_values = problem->Values();
      chosen_ridge_notes = ridge_notes;
    }
  };
  // The start points first: the multistart abandons its short solves against their optima
  // and skips candidates that would end in them.
  for (size_t i = 0; i < first_candidate; ++i) refine(i);
  if (options.use_global_start) {
    GlobalStartOptions global = options.global;
    global.known_optima = optima;
    global.known_costs = optimum_costs;
    problem->SetValues(starts[0]);  // the unsearched variables keep the start's values
    if (!RunGlobalStart(global, problem, &summary->global)) {
      summary->message = "global start: " + summary->global.message;
      return false;
    }
    for (const std::vector<double>& c : summary->global.candidates) starts.push_back(c);
    for (size_t i = first_candidate; i < starts.size(); ++i) refine(i);
  }
  if (summary->chosen < 0) {
    summary->message = "no local refinement succeeded: " + last_failure;
    return false;
  }
  problem->SetValues(best_values);
  NoteGlobalOutcome(*summary, extra_starts.size(), &summary->notes, &summary->findings);
  summary->notes.insert(summary->notes.end(), chosen_ridge_notes.begin(), chosen_ridge_notes.end());
  OrderExchangeable(problem, &summary->notes);

  if (options.compute_uncertainty) {
    // The filter-error method's J'J is the Fisher information once its likelihood residuals
    // are centred at the optimum (filter_error_cost.h); the solve's offsets are put back after.
    const std::vector<double> solve_offsets = problem->CentreLikelihood();
    // One Jet simulation at the optimum serves the HAC and the local analysis.
    SolutionJacobian solution;
    UncertaintyOptions uncertainty = options.uncertainty;
    // One Jacobian evaluation each for the HAC and the local analysis, on one thread: Ceres'
    // threaded evaluation sums in an order that depends on the thread count, and the
    // standard errors must not (a small cost beside the solve).
    uncertainty.hac.num_threads = 1;
    if (!ComputeStageUncertainty(uncertainty, problem, best_cost, &summary->uncertainty,
                                 &summary->notes, &summary->findings, &solution) ||
        !summary->uncertainty.block_variables.empty()) {
      summary->notes.push_back("uncertainty: " + summary->uncertainty.message);
    }
    LocalAnalysisOptions analysis;
    analysis.num_threads = 1;  // as the HAC's Jacobian above, when it is evaluated here
    const bool evaluated = solution.data_rows > 0;
    if (!ComputeLocalAnalysis(analysis, problem, &summary->analysis,
                              evaluated ? &solution : nullptr)) {
      summary->notes.push_back("local analysis: " + summary->analysis.message);
    }
    problem->RestoreOffsets(solve_offsets);
  }
  // The solve and the Jacobian at the optimum are done: the cached evaluations (a Jacobian
  // per experiment) are not kept with the results.
  problem->ReleaseEvaluationCaches();
  if (!EvaluateFit(*problem, &summary->fits, &summary->message)) return false;
  summary->usable = true;
  summary->time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return true;
}

}  // namespace vesselid
