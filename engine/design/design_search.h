// The search for the next experiment: a plan (a point z of the unit box, input_commands.h) is
// realised on the current model (planned_record.h), its information computed
// (planned_information.h) and the criterion taken of I_0 + I_plan (design_criterion.h),
// averaged over the ensemble members when the design is robust; a box on the track is a
// constraint on every member's predicted track. Random starts (half of them on the box's
// corners: bang-bang levels) are scored in parallel; the best are refined by NLopt's COBYLA
// (derivative-free, with the box as an inequality constraint: the criterion is not smooth in
// z where a zigzag's switch moves or an input meets its rate limit).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "Eigen/Core"
#include "engine/design/design_options.h"
#include "engine/design/input_commands.h"
#include "engine/design/planned_information.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct DesignContext {
  const ModelHandle* model = nullptr;
  // Parameter vectors the criterion is taken with: the estimate first, then (robust) the
  // ensemble members.
  std::vector<std::vector<double>> members;
  std::vector<double> x0;
  InformationSetup setup;
  Eigen::MatrixXd current;    // I_0 over setup.parameters
  std::vector<double> scale;  // per setup.parameters, s_i
  DesignOptions options;
  DesignLayout layout;
  Actuators actuators;
  double sample_time = 0.0;
  int criterion_parameter = -1;                                // kParameter: its row
  std::vector<std::pair<int, std::pair<double, double>>> box;  // output -> range from start
};

struct PlanEvaluation {
  bool ok = false;
  std::string error;
  double criterion = 0.0;       // mean over the members
  double box_violation = 0.0;   // largest excursion beyond the box over the members' tracks
  PlannedRecord record;         // at the estimate
  Eigen::MatrixXd information;  // the plan's, at the estimate
  // Per member, the predicted standard errors with the plan added.
  std::vector<std::vector<double>> member_std_errors;
};

using ManoeuvreFactory = std::function<Manoeuvre()>;

// `with_members`: over every member (else the estimate alone).
PlanEvaluation EvaluatePlan(const DesignContext& context, const ManoeuvreFactory& make,
                            bool with_members);

// The largest excursion of a record's track beyond the box (0 inside).
double BoxViolation(const DesignContext& context, const PlannedRecord& record);

struct SearchResult {
  std::vector<double> z;
  PlanEvaluation best;
  int evaluations = 0;
  std::string algorithm;
};

bool SearchDesign(const DesignContext& context, SearchResult* result, std::string* error);

}  // namespace vesselid
