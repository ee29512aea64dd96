// What `vesselid design` found: the planned experiment, the standard errors it is predicted
// to leave beside today's and beside those of the standard alternatives of the same duration.
#pragma once

#include <string>
#include <vector>

#include "engine/design/design_options.h"
#include "engine/design/planned_record.h"

namespace vesselid {

// One candidate experiment: the plan or an alternative.
struct PlanSummary {
  std::string name;  // "planned", "zigzag_10_10", ...
  bool ok = false;
  std::string error;               // why it could not be simulated
  PlannedRecord record;            // at the estimate
  std::vector<double> std_errors;  // predicted after adding it, per DesignResult::parameters
  // Robust designs: per parameter, the 5th, 50th and 95th percentiles over the ensemble
  // members (the median: the standard error to expect when the estimate may be wrong).
  std::vector<double> std_error_low, std_error_median, std_error_high;
  double criterion = 0.0;
  double box_violation = 0.0;  // beyond the box, outputs' units (0: inside)
  double duration = 0.0;       // s, the record's
  // Of the largest relative standard error today (DesignResult::widest): today's over this
  // plan's (how many times it shrinks).
  double shrink = 0.0;
};

struct DesignResult {
  std::string run;  // the run's folder
  std::string model, family;
  std::vector<std::string> parameters, parameter_units;  // those designed for
  std::vector<double> values;                            // the estimate
  std::vector<double> current_std_errors;                // today's (+infinity: undetermined)
  int widest = -1;  // the parameter with the largest relative standard error today
  std::vector<std::string> inputs, input_units;  // the model's
  std::vector<bool> input_degrees;               // written in degrees
  std::vector<std::string> outputs, output_units;
  std::vector<double> noise;  // per output, the sigma assumed (NaN: not measured)
  DesignOptions options;
  double duration = 0.0, sample_time = 0.0;
  std::string criterion;  // "D", "A", "E", "parameter T3"
  PlanSummary planned;
  std::vector<PlanSummary> alternatives;
  std::vector<double> design_variables;  // z
  int evaluations = 0;
  std::string algorithm;
  int members = 0;  // ensemble members the criterion averaged over (0: the estimate alone)
  std::vector<std::string> notes;
  // The limits every plan was checked against: per input, whether the planned record stays
  // within [lower, upper] and the rate, and the box (design_limits.h).
  std::vector<std::string> limit_violations;
};

}  // namespace vesselid
