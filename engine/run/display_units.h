// Units values are shown in: the model's unit of each output (ModelInfo::OutputUnit), in
// degrees where the experiment's column was read in degrees (`degrees:`), so that a user sees
// traces, plots and tables in the unit of the data. The engine computes in radians throughout;
// only what is shown is converted (value x scale). Used by the judgement (diagnose/) and the
// outputs alike.
#pragma once

#include <functional>
#include <string>

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

// The display unit of an output of an experiment (OutputDisplayUnit bound to a config).
using DisplayUnitOf =
    std::function<DisplayUnit(const std::string& experiment, const std::string& output)>;

// "psi [deg]", or the label alone without a unit.
std::string WithUnit(const std::string& label, const std::string& unit);

}  // namespace vesselid
