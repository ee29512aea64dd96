// The per-experiment parameters of held-out runs (output/held_out_parameters_report.h) as
// report.html shows them.
#pragma once

#include <string>
#include <vector>

#include "engine/run/display_units.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"

namespace vesselid {

// A table of report.html (estimates, SE, fit % without and with per output, mean row).
std::string HeldOutParametersHtml(const HeldOutParameters& parameters,
                                  const std::vector<ExperimentFit>& with,
                                  const ParameterUnitOf& unit_of = {});

}  // namespace vesselid
