#include "engine/solve/local_solve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/base/parallel_for.h"
#include "engine/base/stop_request.h"
#include "engine/solve/metrics.h"
#include "engine/solve/dense_local_solve.h"
#include "engine/solve/start_failure.h"

namespace vesselid {
namespace {

// Hands each Ceres iteration's cost to the progress callback.
class ProgressReporter : public ceres::IterationCallback {
 public:
  explicit ProgressReporter(const ProgressCallback& progress) : progress_(progress) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    SolveProgress p;
    p.phase = SolveProgress::Phase::kLocal;
    p.iteration = summary.iteration;
    p.cost = summary.cost;
    progress_(p);
    // The progress callback is where a caller notices an interruption (stop_request.h).
    return StopRequested() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const ProgressCallback& progress_;
};

// Abandons the solve when LocalSolveOptions::keep_going says so.
class AbandonCheck : public ceres::IterationCallback {
 public:
  explicit AbandonCheck(const std::function<bool(int, double)>& keep_going)
      : keep_going_(keep_going) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return keep_going_(summary.iteration, summary.cost) ? ceres::SOLVER_CONTINUE
                                                        : ceres::SOLVER_ABORT;
  }

 private:
  const std::function<bool(int, double)>& keep_going_;
};

// Keeps the values of the last iterate Ceres reached with its derivatives evaluated (each
// callback sees the current, accepted iterate: update_state_every_iteration). A step whose
// simulation diverges is rejected by Ceres; one whose values simulate but whose derivatives
// do not (a Jet the double simulation does not form) ends Ceres with FAILURE instead, and the
// solve goes back to this iterate.
class IterateKeeper : public ceres::IterationCallback {
 public:
  explicit IterateKeeper(const OutputErrorProblem* problem) : problem_(problem) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    values_ = problem_->Values();
    iteration_ = summary.iteration;
    return ceres::SOLVER_CONTINUE;
  }
  const std::vector<double>& values() const { return values_; }
  int iteration() const { return iteration_; }

 private:
  const OutputErrorProblem* problem_;
  std::vector<double> values_;
  int iteration_ = -1;
};

// Ends a crawl: LocalSolveOptions::stall_window and stall_tolerance.
class StallCheck : public ceres::IterationCallback {
 public:
  StallCheck(int window, double tolerance) : window_(window), tolerance_(tolerance) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    // best_[i]: the lowest cost up to iteration i (a rejected step reports its own cost).
    best_.push_back(best_.empty() ? summary.cost : std::min(best_.back(), summary.cost));
    const size_t n = best_.size();
    if (n <= static_cast<size_t>(window_)) return ceres::SOLVER_CONTINUE;
    const double before = best_[n - 1 - window_];
    return before - best_.back() < tolerance_ * before ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                                       : ceres::SOLVER_CONTINUE;
  }

 private:
  const int window_;
  const double tolerance_;
  std::vector<double> best_;
};

// The minimiser a local solve runs, chosen once per RunLocalSolve: the reflective region;
// Levenberg-Marquardt on the normal equations (levenberg_marquardt.h: one Jet simulation per
// trial point, where Ceres' bounded line search evaluates a second Jacobian at each
// candidate) when the linear solver is the automatic dense one; otherwise Ceres' own, with
// the configured or the sparse solver.
enum class Minimiser { kReflective, kDenseLevenbergMarquardt, kCeres };

Minimiser ChooseMinimiser(const LocalSolveOptions& local, const ceres::Solver::Options& options,
                          OutputErrorProblem* problem) {
  if (local.trust_region == TrustRegion::kReflective) return Minimiser::kReflective;
  const bool dense = local.trust_region == TrustRegion::kLevenbergMarquardt &&
                     !local.linear_solver &&
                     options.linear_solver_type == ceres::DENSE_NORMAL_CHOLESKY &&
                     CanSolveOnNormalEquations(problem);
  return dense ? Minimiser::kDenseLevenbergMarquardt : Minimiser::kCeres;
}

void Minimize(const ceres::Solver::Options& options, Minimiser minimiser,
              OutputErrorProblem* problem, ceres::Solver::Summary* summary) {
  switch (minimiser) {
    case Minimiser::kReflective:
      SolveOnNormalEquations(DenseMethod::kReflective, options, problem, summary);
      return;
    case Minimiser::kDenseLevenbergMarquardt:
      SolveOnNormalEquations(DenseMethod::kLevenbergMarquardt, options, problem, summary);
      return;
    case Minimiser::kCeres:
      ceres::Solve(options, problem->problem(), summary);
      return;
  }
}

}  // namespace

const char* TrustRegionToString(TrustRegion method) {
  switch (method) {
    case TrustRegion::kLevenbergMarquardt: return "levenberg_marquardt";
    case TrustRegion::kDogleg: return "dogleg";
    case TrustRegion::kReflective: return "reflective";
  }
  return "levenberg_marquardt";
}

bool StringToTrustRegion(const std::string& text, TrustRegion* method) {
  for (TrustRegion m :
       {TrustRegion::kLevenbergMarquardt, TrustRegion::kDogleg, TrustRegion::kReflective}) {
    if (text == TrustRegionToString(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

bool LocalSolveOptions::IsValid(std::string* error) const {
  if (max_iterations < 0)
    *error = "max_iterations must be >= 0";
  else if (!(function_tolerance >= 0.0))
    *error = "function_tolerance must be >= 0";
  else if (!(gradient_tolerance >= 0.0))
    *error = "gradient_tolerance must be >= 0";
  else if (!(parameter_tolerance >= 0.0))
    *error = "parameter_tolerance must be >= 0";
  else if (!(max_time_seconds > 0.0))
    *error = "max_time_seconds must be > 0";
  else if (stall_window < 0 || !(stall_tolerance >= 0.0))
    *error = "stall_window and stall_tolerance must be >= 0";
  else if (num_threads < 0)
    *error = "num_threads must be >= 0 (0: the machine's cores)";
  else if (initial_radius && !(*initial_radius > 0.0 && std::isfinite(*initial_radius)))
    *error = "initial_radius must be a number > 0";
  else
    return true;
  return false;
}

std::string LocalSolveSummary::BriefReport() const {
  if (!run) return "local solve: not run";
  char text[256];
  std::snprintf(text, sizeof(text), "local solve: cost %.6e -> %.6e, %d iterations, %.3f s, %s",
                initial_cost, final_cost, iterations, time_seconds, termination.c_str());
  return text;
}

ceres::LinearSolverType AutomaticLinearSolver(const OutputErrorProblem& problem) {
  constexpr int kDenseLimit = 60;  // free unknowns whose dense J'J costs little to form
  int per_experiment = 0;
  for (const Variable& v : problem.variables()) {
    if (v.free && v.experiment >= 0) ++per_experiment;
  }
  return per_experiment > 0 && problem.num_free() > kDenseLimit ? ceres::SPARSE_NORMAL_CHOLESKY
                                                                 : ceres::DENSE_NORMAL_CHOLESKY;
}

namespace {

// A failed solve's reason as a user can act on it (Ceres speaks of its own options).
std::string InEngineWords(const ceres::Solver::Summary& summary) {
  if (summary.message.find("max_num_consecutive_invalid_steps") != std::string::npos) {
    return "from this start every step the solver tried made a simulation diverge or the "
           "cost non-finite; no step could be taken (Ceres: " +
           summary.message + ")";
  }
  return summary.message;
}

// Adds a Ceres solve's iterations, work and costs after its start (cost_history holds the
// cost it started from) to `summary`; its termination becomes the summary's.
void AddSolve(const ceres::Solver::Summary& solve, LocalSolveSummary* summary) {
  summary->iterations += static_cast<int>(solve.iterations.size()) - 1;
  summary->successful_steps += solve.num_successful_steps;
  summary->unsuccessful_steps += solve.num_unsuccessful_steps;
  summary->time_seconds += solve.total_time_in_seconds;
  summary->residual_seconds += solve.residual_evaluation_time_in_seconds;
  summary->jacobian_seconds += solve.jacobian_evaluation_time_in_seconds;
  summary->linear_solver_seconds += solve.linear_solver_time_in_seconds;
  summary->residual_evaluations += solve.num_residual_evaluations;
  summary->jacobian_evaluations += solve.num_jacobian_evaluations;
  summary->termination = ceres::TerminationTypeToString(solve.termination_type);
  summary->message = solve.message;
  for (size_t i = 1; i < solve.iterations.size(); ++i) {
    summary->cost_history.push_back(solve.iterations[i].cost);
  }
}

// The held continuation stops when 5 iterations gained less than 1e-4 of the cost.
constexpr int kHeldStallWindow = 5;
constexpr double kHeldStallTolerance = 1e-4;

// Free unknowns Ceres left on a bound (within round-off), whose blocks are not held.
std::vector<const Variable*> AtBound(OutputErrorProblem* problem) {
  std::vector<const Variable*> at;
  for (const Variable& v : problem->variables()) {
    if (!v.free || problem->problem()->IsParameterBlockConstant(v.block)) continue;
    const double x = v.value();
    auto on = [x](double bound) {
      return std::isfinite(bound) && std::abs(x - bound) <= 1e-9 * std::max(1.0, std::abs(bound));
    };
    if (on(v.lower) || on(v.upper)) at.push_back(&v);
  }
  return at;
}

// Ceres projects its trust-region steps onto the bounds, and with an unknown on its bound the
// projected steps can stall short of the optimum: the tanker's second order stopped at 1.10x
// the cost it reaches with T2 held on its 2 s bound (the cost SciPy's reflective trust region
// reaches, tests/benchmarks/peer). So a solve that ends with unknowns on their bounds goes on
// with them held there, within the iterations and time the first solve left, and that is
// kept when it lowers the cost (summed in the problem's own order, as the reported costs).
void ContinueWithBoundsHeld(ceres::Solver::Options options, const LocalSolveOptions& local,
                            Minimiser minimiser, ProgressReporter* reporter, OutputErrorProblem* problem,
                            LocalSolveSummary* summary) {
  options.max_num_iterations = local.max_iterations - summary->iterations;
  options.max_solver_time_in_seconds = local.max_time_seconds - summary->time_seconds;
  if (options.max_num_iterations <= 0 || !(options.max_solver_time_in_seconds > 0.0)) return;
  const std::vector<const Variable*> held = AtBound(problem);
  int free = 0;
  for (const Variable& v : problem->variables()) {
    free += v.free && !problem->problem()->IsParameterBlockConstant(v.block);
  }
  if (held.empty() || static_cast<int>(held.size()) == free) return;
  const std::vector<double> before = problem->Values();
  // A fresh stall check (the first solve's holds its own history), by default one that ends
  // a crawl: on an input-gain campaign a held continuation otherwise spent 70 iterations
  // gaining 5 % (most of it in the first 5). The progress goes on.
  StallCheck stall(local.stall_window > 0 ? local.stall_window : kHeldStallWindow,
                   local.stall_window > 0 ? local.stall_tolerance : kHeldStallTolerance);
  options.callbacks.clear();
  if (reporter != nullptr) options.callbacks.push_back(reporter);
  options.callbacks.push_back(&stall);
  for (const Variable* v : held) problem->problem()->SetParameterBlockConstant(v->block);
  ceres::Solver::Summary again;
  Minimize(options, minimiser, problem, &again);
  for (const Variable* v : held) problem->problem()->SetParameterBlockVariable(v->block);
  double after_cost = 0.0;
  if (!again.IsSolutionUsable() || !problem->Cost(&after_cost) ||
      !(after_cost < summary->final_cost)) {
    problem->SetValues(before);
    return;
  }
  summary->final_cost = after_cost;
  AddSolve(again, summary);
  summary->cost_history.back() = after_cost;
}

// Levenberg-Marquardt on the normal equations from its first radius 1 can crawl where the
// start lies near a region the simulation cannot run: a first-order model's K of the wrong
// sign from T = 2 s ended at 0.15 after 200 iterations, where from 1e4 it converges in 8. A
// solve from the configured start that ends without converging (not on its time limit), given
// at least kRetryMinIterations, is run again from that start at kNearOptimumRadius, and the
// lower cost is kept; its iterations and time are counted either way. A shorter
// max_iterations is an early stop the config asks for (configs/eriksen_2dof.yaml).
constexpr int kRetryMinIterations = 100;
void RetryNearlyGaussNewton(ceres::Solver::Options options, const LocalSolveOptions& local,
                            Minimiser minimiser, const std::vector<double>& start, ProgressReporter* reporter,
                            OutputErrorProblem* problem, LocalSolveSummary* summary) {
  const std::vector<double> end = problem->Values();
  problem->SetValues(start);
  options.initial_trust_region_radius = kNearOptimumRadius;
  options.max_trust_region_radius = std::max(options.max_trust_region_radius, kNearOptimumRadius);
  options.callbacks.clear();
  if (reporter != nullptr) options.callbacks.push_back(reporter);
  StallCheck stall(local.stall_window, local.stall_tolerance);
  if (local.stall_window > 0) options.callbacks.push_back(&stall);
  ceres::Solver::Summary again;
  Minimize(options, minimiser, problem, &again);
  double cost = 0.0;
  if (!again.IsSolutionUsable() || !problem->Cost(&cost) || !(cost < summary->final_cost)) {
    problem->SetValues(end);
    summary->iterations += static_cast<int>(again.iterations.size()) - 1;
    summary->time_seconds += again.total_time_in_seconds;
    return;
  }
  summary->final_cost = cost;
  AddSolve(again, summary);
  summary->message = "from the start again at radius 1e4 (the solve from radius 1 did not "
                     "converge): " + again.message;
  summary->cost_history.back() = cost;
}

}  // namespace

bool RunLocalSolve(const LocalSolveOptions& options, OutputErrorProblem* problem,
                   LocalSolveSummary* summary) {
  *summary = LocalSolveSummary();
  std::string error;
  if (!options.IsValid(&error)) {
    summary->message = error;
    return false;
  }
  ceres::Solver::Options ceres_options;
  ceres_options.trust_region_strategy_type =
      options.trust_region == TrustRegion::kDogleg ? ceres::DOGLEG : ceres::LEVENBERG_MARQUARDT;
  ceres_options.linear_solver_type = options.linear_solver.value_or(AutomaticLinearSolver(*problem));
  ceres_options.max_num_iterations = options.max_iterations;
  const Minimiser minimiser = ChooseMinimiser(options, ceres_options, problem);
  const double radius = options.initial_radius.value_or(
      minimiser == Minimiser::kDenseLevenbergMarquardt ? kFarStartRadius : kNearOptimumRadius);
  ceres_options.initial_trust_region_radius = radius;
  // Ceres requires max_trust_region_radius >= the initial one.
  ceres_options.max_trust_region_radius =
      std::max(ceres_options.max_trust_region_radius, radius);
  ceres_options.function_tolerance = options.function_tolerance;
  ceres_options.gradient_tolerance = options.gradient_tolerance;
  ceres_options.parameter_tolerance = options.parameter_tolerance;
  ceres_options.max_solver_time_in_seconds = options.max_time_seconds;
  ceres_options.num_threads = ParallelThreads(options.num_threads);
  ceres_options.logging_type = ceres::SILENT;
  if (!ceres_options.IsValid(&error)) {
    summary->message = error;
    return false;
  }
  ProgressReporter reporter(options.progress);
  if (options.progress) ceres_options.callbacks.push_back(&reporter);
  const std::vector<double> start = problem->Values();
  // Ceres sums the cost in the order of its reordered program, per thread and then over its
  // threads, so the last bits of its costs depend on the thread count. The costs reported
  // (and the residual variance the standard errors take from them) are summed in the
  // problem's own order instead, one evaluation each: the same numbers on any number of
  // threads.
  const bool threaded = problem->problem()->NumResidualBlocks() > 1;
  double ordered_initial = -1.0;
  if (threaded && !problem->Cost(&ordered_initial)) ordered_initial = -1.0;
  AbandonCheck abandon(options.keep_going);
  if (options.keep_going) {
    ceres_options.callbacks.push_back(&abandon);
    ceres_options.update_state_every_iteration = true;  // keep_going may read the values
  }
  StallCheck stall(options.stall_window, options.stall_tolerance);
  if (options.stall_window > 0) ceres_options.callbacks.push_back(&stall);
  IterateKeeper keeper(problem);
  ceres_options.callbacks.push_back(&keeper);
  ceres_options.update_state_every_iteration = true;
  ceres::Solver::Summary ceres_summary;
  Minimize(ceres_options, minimiser, problem, &ceres_summary);
  if (threaded && ceres_summary.initial_cost >= 0.0 && ordered_initial >= 0.0) {
    ceres_summary.initial_cost = ordered_initial;
    if (!ceres_summary.iterations.empty()) ceres_summary.iterations.front().cost = ordered_initial;
  }
  double ordered_final = 0.0;
  if (threaded && ceres_summary.IsSolutionUsable() && problem->Cost(&ordered_final)) {
    ceres_summary.final_cost = ordered_final;
  }
  summary->run = true;
  summary->usable = ceres_summary.IsSolutionUsable();
  std::string stopped_at;
  double kept_cost = 0.0;
  if (!summary->usable && ceres_summary.termination_type == ceres::FAILURE &&
      keeper.iteration() > 0) {
    problem->SetValues(keeper.values());
    if (problem->Cost(&kept_cost) && std::isfinite(kept_cost)) {
      summary->usable = true;
      stopped_at = "the solve stopped after iteration " + std::to_string(keeper.iteration()) +
                   " (" + InEngineWords(ceres_summary) +
                   ") and keeps the last iterate it reached: its next accepted step could not "
                   "be evaluated with derivatives";
    }
  }
  summary->initial_cost = ceres_summary.initial_cost;
  summary->final_cost = ceres_summary.final_cost;
  if (!ceres_summary.iterations.empty()) {
    summary->cost_history.push_back(ceres_summary.iterations.front().cost);
  }
  AddSolve(ceres_summary, summary);
  if (!stopped_at.empty()) {
    summary->final_cost = kept_cost;
    summary->termination = kStoppedAtFailedStep;
    summary->message = stopped_at;
  }
  if (!options.initial_radius && summary->usable && stopped_at.empty() &&
      ceres_summary.termination_type == ceres::NO_CONVERGENCE &&
      options.max_iterations >= kRetryMinIterations &&
      ceres_summary.message.find("time") == std::string::npos &&
      minimiser == Minimiser::kDenseLevenbergMarquardt) {
    RetryNearlyGaussNewton(ceres_options, options, minimiser, start, options.progress ? &reporter : nullptr,
                           problem, summary);
  }
  // Not after an abandoned solve (keep_going: its caller wants it stopped).
  if (options.hold_bounds_at_end && summary->usable && stopped_at.empty() &&
      std::isfinite(summary->final_cost) &&
      ceres_summary.termination_type != ceres::USER_FAILURE) {
    ContinueWithBoundsHeld(ceres_options, options, minimiser,
                           options.progress ? &reporter : nullptr, problem, summary);
  }
  if (!summary->usable && ceres_summary.initial_cost < 0) {
    // Name the experiment, time, outputs and inputs (the values are still the start values).
    const std::string failure = StartFailure(problem);
    summary->message =
        failure.empty()
            ? "the cost is not finite at the start values (a weight or data value too large?)"
            : failure;
  } else if (summary->usable && !std::isfinite(summary->final_cost)) {
    summary->usable = false;
    summary->termination = "FAILURE";
    summary->message = "the cost is not finite (weights or data too large?)";
  } else if (!summary->usable) {
    summary->message = InEngineWords(ceres_summary);
  }
  return summary->usable;
}

}  // namespace vesselid
