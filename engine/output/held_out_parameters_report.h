// The per-experiment parameters of held-out runs (HeldOutParameters, held_out.h) as
// results.json, report.txt and report.html show them: per held-out run each parameter's
// estimate with its standard error, and per output the fit % without them (held at their
// start) beside the fit with them, so that the user sees what, e.g., a rudder bias per run
// buys: "zz3: delta_0 = 0.041 ± 0.0003; psi fit 15.5 % without delta_0, 94.8 % with".
#pragma once

#include <string>
#include <vector>

#include "engine/run/display_units.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// {"per_experiment": "fit" | "hold", "parameters": [...], "runs": [{"experiment",
// "estimates": {name: {value, std_error, start, lower, upper, undetermined}},
// "fit_percent": {output: {with, without}}, "mae": {output: {with, without}}}],
// "mean_fit_percent": {output: {with, without}}}; `with` are the held-out fits.
nlohmann::json HeldOutParametersToJson(const HeldOutParameters& parameters,
                                       const std::vector<ExperimentFit>& with);

// Lines of report.txt, each starting with `indent`; empty when there are no parameters.
// Estimates in `unit_of`'s unit (display_units.h; empty: the model's).
std::string HeldOutParametersText(const HeldOutParameters& parameters,
                                  const std::vector<ExperimentFit>& with,
                                  const std::string& indent, const ParameterUnitOf& unit_of = {});

// A table of report.html (estimates, SE, fit % without and with per output, mean row).
std::string HeldOutParametersHtml(const HeldOutParameters& parameters,
                                  const std::vector<ExperimentFit>& with,
                                  const ParameterUnitOf& unit_of = {});

}  // namespace vesselid
