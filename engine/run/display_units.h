// Units values are shown in: the model's unit of each output (ModelInfo::OutputUnit), in
// degrees where the experiment's column was read in degrees (`degrees:`), so that a user sees
// traces, plots and tables in the unit of the data. The engine computes in radians throughout;
// only what is shown is converted (value x scale). Used by the judgement (diagnose/) and the
// outputs alike.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/run/records.h"
#include "engine/run/run_config.h"

namespace vesselid {

struct DisplayUnit {
  std::string unit;  // "deg", "deg/s", "m", ... ("" when the model does not state it)
  double scale = 1.0;
};

// Output `output` of experiment `experiment` (a record, or one of its segments "<name>@<id>"
// or pieces "<name>#<k>"): "rad" -> "deg" (and "rad/s" -> "deg/s") with scale 180/pi when the
// record maps the output to a column listed in its `degrees:`.
DisplayUnit OutputDisplayUnit(const RunConfig& config, const std::string& experiment,
                              const std::string& output);

// Parameter `name` as the outputs name it: "delta_0" (shared), "delta_0[zz1]" (per
// experiment) or "x0.psi[zz1]" (an initial state). Its model unit (ModelInfo::ParameterUnit,
// StateUnit for an initial state), "rad" -> "deg" with scale 180/pi where the channel it is an
// angle of (ModelInfo::parameter_channels; an initial state: its same-named output) is read in
// degrees: in the named experiment, or, for a shared value, in every experiment that maps the
// channel. Not stated: {"", 1}.
DisplayUnit ParameterDisplayUnit(const RunConfig& config, const std::string& name);

// The model's unit of parameter `name` (named as above; "" when not stated) and in `channel`
// (may be null) the channel it is an angle of ("" for none).
std::string ParameterModelUnit(const ModelInfo& info, const std::string& name,
                               std::string* channel = nullptr);

// The display unit of an output of an experiment (OutputDisplayUnit bound to a config).
using DisplayUnitOf =
    std::function<DisplayUnit(const std::string& experiment, const std::string& output)>;

// The display unit of a parameter (ParameterDisplayUnit bound to a config).
using ParameterUnitOf = std::function<DisplayUnit(const std::string& name)>;

// The model inputs and outputs the run's first experiment reads in degrees (its `degrees:`):
// what a user's tables for the model (Python's simulate, the traces) hold in degrees; a state
// named as such an output is in degrees there too.
std::vector<std::string> DegreeChannels(const RunConfig& config);

// value x scale printed with `format`, then " unit" when the unit is stated: "2.5 deg".
std::string ShownValue(double value, const DisplayUnit& unit, const char* format = "%.6g");

// OutputDisplayUnit and ParameterDisplayUnit bound to `config` (which must outlive them).
DisplayUnitOf OutputUnits(const RunConfig& config);
ParameterUnitOf ParameterUnits(const RunConfig& config);

// "psi [deg]", or the label alone without a unit.
std::string WithUnit(const std::string& label, const std::string& unit);

}  // namespace vesselid
