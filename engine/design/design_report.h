// The files of `vesselid design` (published as one set into <run-out>/design or --out):
//   design.json         predicted standard errors (current, planned, each alternative), the
//                       plans' durations, criteria and box checks, the limits check;
//   design.txt          the same as a table (also printed);
//   planned_input.csv   t and every model input of the plan, in the config's units (degrees
//                       where an input is given in degrees): for the logger or autopilot script;
//   predicted.csv       t, the inputs and the outputs the current model predicts on the plan;
//   report.html         the tables, the standard errors as a plot, the plan and its track.
#pragma once

#include <string>

#include "engine/design/design_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json DesignToJson(const DesignResult& result);
std::string DesignText(const DesignResult& result);
std::string PlannedInputCsv(const DesignResult& result);
std::string PredictedCsv(const DesignResult& result);
std::string DesignHtml(const DesignResult& result);

// Writes the files into `out_dir` (empty: <run>/design); false with a message.
bool WriteDesign(const DesignResult& result, std::string out_dir, std::string* error);

}  // namespace vesselid
