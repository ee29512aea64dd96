// Turning circle figures of a run (RunResult::turning_circles, turning_figures.h) as
// results.json, report.txt and report.html show them (report/turning_html.h): per turning
// record the rudder angle and side, and measured against simulated the advance, transfer and
// tactical diameter (in the track's unit and in ship lengths where the model's options give a
// `length`) and the times to 90 and 180 deg of heading change, IMO MSC.137(76) definitions.
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// [{"stage", "experiment", "held_out", "rudder_deg", "side", "unit", "measured": {...},
//   "simulated": {"advance", "transfer", "tactical_diameter", "time_to_90_s",
//   "time_to_180_s"}, "error_percent": {"advance", "transfer", "tactical_diameter"}}];
// unknown figures are null.
nlohmann::json TurningRunsToJson(const std::vector<TurningRun>& runs);

// The figures' definitions, as the reports state them.
extern const char kTurningDefinitions[];

// (simulated - measured) / measured in %, NaN where either is unknown or measured is 0.
double TurningErrorPercent(double measured, double simulated);

// A report.txt section; empty without turning circles.
std::string TurningRunsText(const std::vector<TurningRun>& runs);

}  // namespace vesselid
