#include "engine/design/design_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <random>

#include "engine/base/parallel_for.h"
#include "engine/design/design_criterion.h"
#include "nlopt.hpp"

namespace vesselid {
namespace {

Eigen::MatrixXd Relative(const DesignContext& c, const Eigen::MatrixXd& information) {
  const Eigen::VectorXd s = Eigen::Map<const Eigen::VectorXd>(c.scale.data(), c.scale.size());
  return s.asDiagonal() * information * s.asDiagonal();
}

// Infeasible plans rank after every feasible one, by how far they leave the box.
double Score(const PlanEvaluation& e) {
  if (!e.ok) return std::numeric_limits<double>::infinity();
  return e.box_violation > 0.0 ? 1e30 * (1.0 + e.box_violation) : e.criterion;
}

}  // namespace

double BoxViolation(const DesignContext& c, const PlannedRecord& record) {
  double worst = 0.0;
  for (const auto& [output, range] : c.box) {
    const double start = record.outputs(0, output);
    for (int k = 0; k < record.outputs.rows(); ++k) {
      const double d = record.outputs(k, output) - start;
      worst = std::max({worst, range.first - d, d - range.second});
    }
  }
  return worst;
}

PlanEvaluation EvaluatePlan(const DesignContext& c, const ManoeuvreFactory& make,
                            bool with_members) {
  PlanEvaluation e;
  const size_t members = with_members ? c.members.size() : 1;
  double sum = 0.0;
  for (size_t m = 0; m < members; ++m) {
    const std::vector<double>& p = c.members[m];
    const Manoeuvre manoeuvre = make();
    PlannedRecord record;
    if (!RealizePlan(*c.model, p, c.x0, c.layout.duration, c.sample_time, c.setup.max_step,
                     c.actuators, manoeuvre.command, &record, manoeuvre.Stop())) {
      if (m == 0) {
        e.error = "the plan's simulation diverges";
        return e;
      }
      continue;  // a member that diverges on the plan does not vote
    }
    Eigen::MatrixXd information;
    std::string error;
    if (!PlannedInformation(*c.model, record, p, c.x0, c.setup, &information, &error)) {
      if (m == 0) {
        e.error = error;
        return e;
      }
      continue;
    }
    const Eigen::MatrixXd total = c.current + information;
    sum += CriterionValue(Relative(c, total), c.options.criterion, c.criterion_parameter);
    e.box_violation = std::max(e.box_violation, BoxViolation(c, record));
    e.member_std_errors.push_back(PredictedStdErrors(total, c.scale));
    if (m == 0) {
      e.record = std::move(record);
      e.information = std::move(information);
    }
  }
  e.criterion = sum / static_cast<double>(e.member_std_errors.size());
  e.ok = true;
  return e;
}

bool SearchDesign(const DesignContext& c, SearchResult* result, std::string* error) {
  const int n = c.layout.variables;
  const bool robust = c.options.ensemble_members > 0;
  auto plan_of = [&c](const std::vector<double>& z) {
    return [&c, z] { return CommandOf(c.options, c.layout, z); };
  };
  // Random starts: even ones on the unit box's corners (bang-bang), odd ones inside; the first
  // holds every input at its value (inside any box, so that the search has a feasible start).
  const int starts = std::max(2, c.options.starts);
  std::vector<std::vector<double>> z(starts, std::vector<double>(n));
  std::mt19937_64 random(c.options.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  z[0] = QuietDesign(c.options, c.layout);
  for (int s = 1; s < starts; ++s) {
    for (int i = 0; i < n; ++i) {
      z[s][i] = s % 2 == 0 ? (uniform(random) < 0.5 ? 0.0 : 1.0) : uniform(random);
    }
  }
  std::vector<double> score(starts);
  ParallelFor(starts, c.options.threads,
              [&](int s) { score[s] = Score(EvaluatePlan(c, plan_of(z[s]), robust)); });
  int evaluations = starts;
  std::vector<int> order(starts);
  for (int s = 0; s < starts; ++s) order[s] = s;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return score[a] < score[b]; });
  if (!std::isfinite(score[order[0]])) {
    const PlanEvaluation first = EvaluatePlan(c, plan_of(z[order[0]]), false);
    *error = "no start of the search could be simulated: " + first.error;
    return false;
  }
  // COBYLA from the best starts, the box as a constraint.
  const int refined = std::min(std::max(1, c.options.refined), starts);
  const int budget = std::max(2 * n + 2, c.options.max_evaluations / refined);
  std::vector<std::vector<double>> best_z(refined);
  std::vector<double> best_score(refined);
  std::vector<int> used(refined, 0);
  ParallelFor(refined, c.options.threads, [&](int r) {
    std::vector<double> x = z[order[r]];
    // Coordinate exchange (the classic search of discrete input designs): each variable in
    // turn tried at 0, 1/2 and 1, the best kept, in passes until none improves or half the
    // budget is spent; it finds the bang-bang switching a local search misses.
    double current = score[order[r]];
    int spent = 0;
    for (bool improved = true; improved && spent + 2 * n <= budget / 2;) {
      improved = false;
      for (int i = 0; i < n; ++i) {
        const double kept = x[i];
        double best_value = kept;
        for (double trial : {0.0, 0.5, 1.0}) {
          if (trial == kept) continue;
          x[i] = trial;
          const double value = Score(EvaluatePlan(c, plan_of(x), robust));
          ++spent;
          if (value < current - 1e-12 * std::abs(current)) {
            current = value;
            best_value = trial;
            improved = true;
          }
        }
        x[i] = best_value;
      }
    }
    used[r] += spent;
    nlopt::opt local(nlopt::LN_COBYLA, n);
    local.set_lower_bounds(std::vector<double>(n, 0.0));
    local.set_upper_bounds(std::vector<double>(n, 1.0));
    local.set_maxeval(std::max(2 * n + 2, budget - spent));
    local.set_xtol_rel(1e-4);
    local.set_initial_step(std::vector<double>(n, 0.25));
    struct Memo {
      const DesignContext* c;
      std::function<ManoeuvreFactory(const std::vector<double>&)> plan_of;
      bool robust;
      int* count;
      std::vector<double> last_z;
      PlanEvaluation last;
      const PlanEvaluation& At(const std::vector<double>& x) {
        if (x != last_z || !last.ok) {
          last = EvaluatePlan(*c, plan_of(x), robust);
          last_z = x;
          ++*count;
        }
        return last;
      }
    } memo{&c, plan_of, robust, &used[r], {}, {}};
    local.set_min_objective(
        [](const std::vector<double>& x, std::vector<double>&, void* data) {
          const PlanEvaluation& e = static_cast<Memo*>(data)->At(x);
          return e.ok ? e.criterion : 1e30;
        },
        &memo);
    if (!c.box.empty()) {
      local.add_inequality_constraint(
          [](const std::vector<double>& x, std::vector<double>&, void* data) {
            const PlanEvaluation& e = static_cast<Memo*>(data)->At(x);
            return e.ok ? e.box_violation : 1e30;
          },
          &memo, 1e-6);
    }
    const std::vector<double> exchanged = x;
    double value = current;
    try {
      local.optimize(x, value);
    } catch (const std::exception&) {
      // A roundoff or forced stop keeps the best point COBYLA reached.
    }
    best_z[r] = x;
    best_score[r] = Score(EvaluatePlan(c, plan_of(x), robust));
    if (!(best_score[r] <= current)) {  // never worse than the exchange's
      best_z[r] = exchanged;
      best_score[r] = current;
    }
  });
  int winner = 0;
  for (int r = 0; r < refined; ++r) {
    evaluations += used[r];
    if (best_score[r] < best_score[winner]) winner = r;
  }
  result->z = best_z[winner];
  result->best = EvaluatePlan(c, plan_of(result->z), true);
  result->evaluations = evaluations;
  result->algorithm = "random starts, coordinate exchange, NLopt LN_COBYLA";
  return result->best.ok;
}

}  // namespace vesselid
