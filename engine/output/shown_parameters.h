// A parameter's numbers as the outputs show them: in the unit its data came in
// (display_units.h: a rudder bias in degrees where the rudder column was read in degrees).
// The engine keeps every value in the model's unit; these copies scale value, start, standard
// error, bounds, interval and per-run range by the unit's scale for report.txt and report.html.
// results.json keeps the model's unit and states both (ParameterUnitJson).
#pragma once

#include "engine/output/parameter_summary.h"
#include "engine/run/display_units.h"
#include "engine/run/run_result.h"

namespace vesselid {

Estimate Shown(const Estimate& estimate, const DisplayUnit& unit);
FinalParameter Shown(const FinalParameter& parameter, const DisplayUnit& unit);
ParameterReport Shown(const ParameterReport& report, const DisplayUnit& unit);

}  // namespace vesselid
