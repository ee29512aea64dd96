#include "engine/solve/multistart.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>

#include "engine/base/parallel_for.h"
#include "engine/base/stop_request.h"
#include "engine/solve/halton_sequence.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/search_box.h"

namespace vesselid {
namespace {

enum class PointStatus { kDiverged, kAbandoned, kEnded };

struct PointResult {
  PointStatus status = PointStatus::kDiverged;
  std::vector<double> values;  // end point, exchangeable pairs ordered
  double cost = std::numeric_limits<double>::infinity();
  int iterations = 0;
};

// Problems for the worker threads: each body borrows one and gives it back.
class ProblemPool {
 public:
  ProblemPool(OutputErrorProblem* problem, int size) : free_{problem} {
    for (int i = 1; i < size; ++i) {
      owned_.push_back(problem->Clone());
      free_.push_back(owned_.back().get());
    }
  }
  OutputErrorProblem* Borrow() {
    std::lock_guard<std::mutex> lock(mutex_);
    OutputErrorProblem* p = free_.back();
    free_.pop_back();
    return p;
  }
  void Return(OutputErrorProblem* p) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(p);
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<OutputErrorProblem>> owned_;
  std::vector<OutputErrorProblem*> free_;
};

// A short solve from `start`, whose cost the screening found finite.
PointResult ShortSolve(const GlobalStartOptions& options, const SearchBox& box,
                       const std::vector<double>& start, double best_before,
                       OutputErrorProblem* problem) {
  PointResult result;
  problem->SetValues(start);
  LocalSolveOptions local;
  local.max_iterations = options.short_iterations;
  // A short solve is a fast descent, and one that goes wrong is dropped.
  local.initial_radius = kNearOptimumRadius;
  local.num_threads = 1;
  local.hold_bounds_at_end = false;  // a short solve: its refinement does that
  bool abandoned = false;
  if (std::isfinite(best_before)) {
    local.keep_going = [&](int iteration, double c) {
      abandoned = iteration >= 1 && c > kMultistartAbandonFactor * best_before;
      return !abandoned;
    };
  }
  LocalSolveSummary summary;
  RunLocalSolve(local, problem, &summary);
  result.iterations = std::max(0, summary.iterations);
  if (abandoned) {
    result.status = PointStatus::kAbandoned;
    return result;
  }
  // Ceres keeps the last accepted point; a solve whose every step diverged ends unusable.
  if (!summary.usable || !std::isfinite(summary.final_cost)) return result;
  result.status = PointStatus::kEnded;
  result.cost = summary.final_cost;
  const std::vector<double> end = problem->Values();
  result.values = box.Values(box.Coordinates(end), end);
  return result;
}

// Relative cost margin within which an end point counts as no better than a known optimum
// (the last bits of a cost depend on the summation order).
constexpr double kSameCost = 1e-6;

}  // namespace

int ShortSolveCount(int finite, int dimension, int candidates) {
  return std::min(finite, std::max(2 * dimension, 2 * candidates));
}

bool RunMultistart(const GlobalStartOptions& options, OutputErrorProblem* problem,
                   GlobalStartSummary* summary) {
  const auto start_time = std::chrono::steady_clock::now();
  *summary = GlobalStartSummary();
  const SearchBox box(*problem);
  summary->variables = box.names();
  for (int k = 0; k < box.dimension(); ++k) {
    if (box.around_start(k)) summary->around_start.push_back(box.names()[k]);
  }
  if (box.dimension() == 0) {
    summary->message = "no free parameter to search";
    return false;
  }
  const std::vector<double> base = problem->Values();
  const HaltonSequence halton(box.dimension(), options.seed);
  std::vector<std::vector<double>> starts;
  for (int i = 0; i < options.points; ++i) starts.push_back(box.Values(halton.Point(i + 1), base));

  const int threads = std::min(ParallelThreads(options.threads), kMultistartBatch);
  ProblemPool pool(problem, std::min(threads, options.points));
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  };

  // Screening: the cost of every point, one simulation each. A stop request (Ctrl-C) leaves
  // the points not yet screened out: 4000 points of a long record take seconds.
  std::vector<double> screened(starts.size(), std::numeric_limits<double>::infinity());
  std::vector<char> unscreened(starts.size(), 0);
  ParallelFor(options.points, threads, [&](int i) {
    // On the calling thread this also asks the embedding program (a Python Ctrl-C), as
    // progress would; the pool's threads have no check of their own (stop_request.h).
    if (PollStopRequest()) {
      unscreened[i] = 1;
      return;
    }
    OutputErrorProblem* p = pool.Borrow();
    p->SetValues(starts[i]);
    double cost = 0.0;
    if (p->Cost(&cost) && std::isfinite(cost)) screened[i] = cost;
    pool.Return(p);
  });
  std::vector<int> ranked;
  for (int i = 0; i < options.points; ++i) {
    if (std::isfinite(screened[i])) {
      ranked.push_back(i);
    } else if (!unscreened[i]) {
      ++summary->failed_evaluations;
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [&](int a, int b) { return screened[a] < screened[b]; });
  ranked.resize(ShortSolveCount(static_cast<int>(ranked.size()), box.dimension(),
                                options.candidates));

  // Short solves are abandoned against the end costs of earlier short solves only: a known
  // optimum's cost is that of a converged solve, which a far point that would lead to a
  // better one may exceed tenfold after its first iteration.
  double known_best = std::numeric_limits<double>::infinity();
  for (double c : options.known_costs) known_best = std::min(known_best, c);
  std::vector<PointResult> results(ranked.size());
  double best = std::numeric_limits<double>::infinity();
  int done = 0;
  const int count_all = static_cast<int>(ranked.size());
  for (int first = 0; first < count_all; first += kMultistartBatch) {
    if (first > 0 && elapsed() > options.max_time_seconds) {
      summary->result = "stopped at max_time";
      break;
    }
    if (first > 0 && StopRequested()) {
      summary->result = "stopped on request";
      break;
    }
    const int count = std::min(kMultistartBatch, count_all - first);
    const double best_before = best;
    ParallelFor(count, threads, [&](int j) {
      OutputErrorProblem* p = pool.Borrow();
      results[first + j] = ShortSolve(options, box, starts[ranked[first + j]], best_before, p);
      pool.Return(p);
    });
    for (int j = 0; j < count; ++j) {
      const PointResult& r = results[first + j];
      summary->short_iterations_total += r.iterations;
      if (r.status == PointStatus::kDiverged) ++summary->failed_evaluations;
      if (r.status == PointStatus::kAbandoned) ++summary->abandoned;
      if (r.status == PointStatus::kEnded) best = std::min(best, r.cost);
      const double found = std::min(best, known_best);
      summary->best_cost_history.push_back(std::isfinite(found) ? found : std::nan(""));
    }
    done = first + count;
    if (options.progress) {
      SolveProgress p;
      p.phase = SolveProgress::Phase::kGlobal;
      p.iteration = done;
      p.cost = std::isfinite(best) ? best : std::nan("");
      options.progress(p);
    }
  }
  problem->SetValues(base);
  summary->run = true;
  summary->evaluations =
      options.points - static_cast<int>(std::count(unscreened.begin(), unscreened.end(), 1));
  summary->short_solves = done;
  if (summary->result.empty()) summary->result = "multistart";

  // Clusters, best end point first: a point within min_separation of a kept one joins it; a
  // point within min_separation of a known optimum at no lower cost is that optimum's.
  std::vector<int> order;
  for (int i = 0; i < done; ++i) {
    if (results[i].status == PointStatus::kEnded) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return results[a].cost < results[b].cost; });
  std::vector<const std::vector<double>*> representatives;
  for (int i : order) {
    bool distinct = true;
    for (const std::vector<double>* c : representatives) {
      distinct = distinct && box.Distance(*c, results[i].values) >= options.min_separation;
    }
    if (!distinct) continue;
    representatives.push_back(&results[i].values);
    ++summary->clusters;
    bool known = false;
    for (size_t k = 0; k < options.known_optima.size() && !known; ++k) {
      known = box.Distance(options.known_optima[k], results[i].values) < options.min_separation &&
              results[i].cost >= (1.0 - kSameCost) * options.known_costs[k];
    }
    if (known) {
      ++summary->known_joined;
    } else if (static_cast<int>(summary->candidates.size()) < options.candidates) {
      summary->candidates.push_back(results[i].values);
      summary->candidate_costs.push_back(results[i].cost);
    }
  }
  summary->best_cost = summary->candidate_costs.empty() ? -1.0 : summary->candidate_costs[0];
  summary->time_seconds = elapsed();
  if (summary->candidates.empty() && options.known_optima.empty()) {
    summary->message = "no short solve of the multistart ended with a finite cost (" +
                       std::to_string(summary->failed_evaluations) + " of " +
                       std::to_string(options.points) + " points diverged)";
    return false;
  }
  return true;
}

}  // namespace vesselid
