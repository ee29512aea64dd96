// The stage key `noise` (model/disturbance.h; docs/models.md "Disturbance models"):
//
//   noise: output_error | filter_error | auto     (the method alone)
//   noise:
//     method: output_error | filter_error | auto
//     angles: rad | deg                      the unit of the angle outputs' sigmas (rad)
//     measurement: {<output>: white | ar1 | {type: white | ar1, sigma, tau, white: true}}
//     process: {<state>: auto | <spectral density, state unit^2/s>}
//     wave: {<output>: auto | {omega, zeta, sigma}}
//     bias: {<output>: auto | {q, initial_sd}}
//     prediction_steps: <k of the held-out k-step-ahead predictions>
//     gain: auto | time_varying              steady-state gain once stationary (auto)
#pragma once

#include <string>

#include "engine/config/yaml_reader.h"
#include "engine/model/disturbance.h"

namespace vesselid {

// Reads `node` (the value of noise at `path`) into `spec`. Fails with the file, line and key
// on an unknown output, state or key, or a value out of its range.
void ReadDisturbance(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     const ModelInfo& info, DisturbanceSpec* spec);

}  // namespace vesselid
