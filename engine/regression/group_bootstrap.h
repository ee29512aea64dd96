// Bootstrap over the groups of a regression's samples (the steady-state groups, contiguous
// blocks or experiments its cross-validation leaves out): replicate r draws, in each stratum
// s of G_s groups, G_s groups with replacement (seeded by CaseSeed(seed, kBootstrapPart, r)),
// refits the estimator with each group's samples counted as often as it was drawn, and keeps
// the estimates theta*_r. Per quantity
//
//   SE = sqrt( sum_r (theta*_r - mean)^2 / (R - 1) ),   interval = [q_0.025, q_0.975]
//
// (percentiles of the replicates, linear interpolation between order statistics), and per
// lasso coefficient the share of replicates where it is exactly zero (selection stability).
// Replicates run in parallel; each depends only on its index, so the result does not depend
// on the thread count.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace vesselid {

inline constexpr int kBootstrapPart = 21;  // CaseSeed part of bootstrap replicates

struct GroupBootstrapOptions {
  int runs = 0;         // replicates; 0: no bootstrap
  unsigned seed = 1;    // of the draws
  int threads = 0;      // worker threads; 0: the machine's cores
  bool hold_lambda = true;  // refit at the selected lambda (false: select it again per draw)
  int blocks = 20;      // least-squares stages: contiguous blocks of the samples drawn

  bool IsValid(std::string* error) const;
};

// A refit on one draw: counts[g] is how often group g (numbered over all strata) was drawn.
// Fills `values` (the bootstrapped quantities, fixed order) and `coefficients` (lasso
// coefficients, for the zero share; may stay empty). False: the draw cannot be fitted (too
// few distinct groups, a failed solve); the replicate is counted as failed and left out.
using BootstrapReplicate = std::function<bool(
    const std::vector<int>& counts, std::vector<double>* values,
    std::vector<double>* coefficients)>;

struct BootstrapSummary {
  int runs = 0;    // replicates drawn (0: no bootstrap)
  int failed = 0;  // of them, not fitted
  int groups = 0;  // groups over all strata
  std::string resampled;  // what a group is, e.g. "steady-state groups and steps"
  bool lambda_held = true;
  std::vector<std::string> names;  // bootstrapped quantities (parameters)
  std::vector<double> std_error, lower, upper;  // SD and 2.5 / 97.5 % percentiles
  std::vector<std::string> coefficient_names;    // lasso coefficients
  std::vector<double> zero_share;                // share of replicates with it exactly 0
  std::string message;  // why a requested bootstrap did not run (then runs is 0)
  double time_seconds = 0.0;

  bool done() const { return runs > 0; }
  // Index of quantity `name`, -1 if it is not bootstrapped.
  int Find(const std::string& name) const;
};

// Stratum sizes G_s (each > 0), the names of the quantities and coefficients the replicate
// fills, and the replicate itself. False with a message if fewer than two replicates fit or
// a replicate returns the wrong number of values.
bool RunGroupBootstrap(const std::vector<int>& strata, const std::vector<std::string>& names,
                       const std::vector<std::string>& coefficient_names,
                       const BootstrapReplicate& replicate, const GroupBootstrapOptions& options,
                       BootstrapSummary* summary, std::string* error);

// Selection stability: a lasso coefficient zero in 20-80 % of the replicates is unstable.
inline bool UnstableSelection(double zero_share) {
  return zero_share >= 0.2 && zero_share <= 0.8;
}

// "bootstrap over 20 contiguous sample blocks, 200 replicates (3 not fitted), lambda held".
std::string BootstrapDescription(const BootstrapSummary& summary);

// Percentile q in [0, 1] of sorted values (linear interpolation between order statistics).
double SortedPercentile(const std::vector<double>& sorted, double q);

}  // namespace vesselid
