// A stage's per-channel noise model (`weights: noise`, noise_weights.h) as results.json,
// report.txt and report.html (report/noise_model_html.h) show it: sigma per compared output in the unit the user reads
// (display_units.h: degrees where the heading column was read in degrees), the re-solves and
// whether it settled. Nothing for a stage with the configured weights.
#pragma once

#include <string>

#include "engine/run/display_units.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// {method, iterations, converged, sigma: {output: value}, units: {output: unit},
//  samples: {output: count}}; null when the stage used the configured weights.
nlohmann::json NoiseModelToJson(const RunConfig& config, const StageResult& stage);

// The unit output `output`'s sigma is shown in (that of the stage's first experiment comparing
// it), and "3 re-solves, settled".
DisplayUnit NoiseUnitOf(const RunConfig& config, const StageResult& stage,
                        const std::string& output);
std::string NoiseSettling(const NoiseModel& noise);

// "  noise model: sigma n 0.0201 m, psi 0.301 deg (weights 1/sigma; 3 re-solves, settled)\n",
// or empty.
std::string NoiseModelText(const RunConfig& config, const StageResult& stage);

}  // namespace vesselid
