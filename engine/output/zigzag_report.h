// Zigzag figures of a run (RunResult::zigzags, zigzag_figures.h) as results.json, report.txt
// and report.html show them (report/zigzag_html.h): per zigzag record the test (delta_z/psi_z), and measured against
// simulated the first and second overshoot angles (deg), the time to the first heading check
// and the period (s), IMO MSC.137(76) definitions.
#pragma once

#include <string>
#include <vector>

#include "engine/output/held_out_zigzags.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// [{"stage", "experiment", "held_out", "rudder_deg", "heading_deg", "measured": {...},
//   "simulated": {"first_overshoot_deg", "second_overshoot_deg", "time_to_first_check_s",
//   "period_s", "executes_s"}}]; unknown figures are null.
nlohmann::json ZigzagRunsToJson(const std::vector<ZigzagRun>& runs);

// The runs as results.json records them (overshoots in degrees: the same numbers), for the
// held-out check (held_out_zigzags.h).
std::vector<ZigzagEntry> ZigzagEntries(const std::vector<ZigzagRun>& runs);

// The figures' definitions (IMO MSC.137(76)), as the reports state them.
extern const char kZigzagDefinitions[];

// The test as flown, "20.0/5.2" (delta_z/psi_z in degrees).
std::string ZigzagTestLabel(const ZigzagRun& run);

// A report.txt section, with the held-out runs against their prediction intervals
// (held_out_zigzags.h) where the run holds zigzags out; empty without zigzags.
std::string ZigzagRunsText(const std::vector<ZigzagRun>& runs);

}  // namespace vesselid
