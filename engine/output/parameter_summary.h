// What the report says of each final parameter besides its value (report.txt, report.html,
// results.json alike):
//   * its bounds (those of the last stage that estimated it) and whether it ends on one (within
//     1e-6 of the bound range, as the stage's note says): its standard error then assumes an
//     interior optimum the data do not have;
//   * its 95 % interval value +- 1.96 SE clipped to the bounds, flagged when clipped;
//   * a fused value outside the range of its stages' estimates, explained: information fusion
//     solves for all shared parameters at once with each stage's covariance, so a parameter
//     correlated with others moves with them and may leave the span of its own estimates.
// And the counts of a run's or a stage's unknowns: shared parameters, per-experiment ones,
// held fixed, and initial states apart.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

struct ParameterReport {
  std::string name;
  // Bounds of the last stage that estimated it (per experiment: those of its per-run values).
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  int bound = 0;  // -1 on the lower bound, +1 on the upper, 0 inside (or not estimated)
  // The 95 % interval clipped to [lower, upper]; NaN without a standard error.
  double interval_low = std::numeric_limits<double>::quiet_NaN();
  double interval_high = std::numeric_limits<double>::quiet_NaN();
  bool clipped = false;
  std::string fusion_note;  // empty unless a fused value lies outside its stages' estimates
};

// One per final parameter, in the order of result.parameters.
std::vector<ParameterReport> ReportParameters(const RunResult& result);

// "on its lower bound 0.001", "interval clipped to the bounds", both, or ""; `unit` follows
// the bound when given ("on its upper bound 5.7 deg").
std::string ParameterFlags(const ParameterReport& report, const std::string& unit = "");

// Counts of unknowns: parameters by role, and initial states apart.
struct UnknownCounts {
  int shared = 0;                 // one value for every experiment (free, shared, isolated)
  int per_experiment = 0;         // parameters with one value per experiment ...
  int per_experiment_values = 0;  // ... and their values
  int fixed = 0;
  int initial_states = 0;  // estimated initial states (values)
};

UnknownCounts CountUnknowns(const std::vector<Estimate>& estimates);
// The final parameters' counts; initial states summed over the stages.
UnknownCounts CountUnknowns(const RunResult& result);

// "3 parameters estimated (1 per experiment: 12 values), 2 held fixed; 24 initial states".
std::string DescribeCounts(const UnknownCounts& counts);

}  // namespace vesselid
