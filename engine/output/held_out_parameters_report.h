// The per-experiment parameters of held-out runs (HeldOutParameters, held_out.h) as
// results.json and report.txt show them (report.html: report/held_out_parameters_html.h): per
// held-out run each parameter's estimate with its standard error, and per output the fit %
// without them (held at the training runs' mean) beside the fit with them, so that the user sees what, e.g., a rudder bias per run
// buys: "zz3: delta_0 = 0.041 ± 0.0003; psi fit 15.5 % without delta_0, 94.8 % with".
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/run/display_units.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// One held-out run: its estimates and, per output, fit % and MAE with and without them
// (NaN where that simulation diverged).
struct HeldOutRunRow {
  std::string experiment;
  std::vector<const Estimate*> estimates;
  std::string diverged_with, diverged_without;
  std::map<std::string, std::pair<double, double>> fit, mae;  // output: (with, without)
};

struct HeldOutParametersTable {
  std::vector<std::string> outputs;  // order of first appearance
  std::vector<HeldOutRunRow> rows;
  // Per output the mean fit % over the runs where both simulations ran, and their count.
  std::map<std::string, std::pair<double, double>> mean_fit;
  std::map<std::string, int> counted;
};

HeldOutParametersTable MakeHeldOutParametersTable(const HeldOutParameters& parameters,
                                                  const std::vector<ExperimentFit>& with);

// "delta_0, x_0": the per-experiment parameters' names.
std::string HeldOutParameterNames(const HeldOutParameters& parameters);

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

}  // namespace vesselid
