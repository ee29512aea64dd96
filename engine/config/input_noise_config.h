// The experiment key `input_noise` (model/input_noise.h):
//
//   input_noise: {<input>: auto}                 spline and corrections chosen from the data
//   input_noise: {<input>: {sigma: auto | <SD in the column's unit>,
//                           knots: auto | <spline knot spacing, s>,
//                           correction: auto | off | <correction spacing, s>}}
#pragma once

#include <string>

#include "engine/config/yaml_reader.h"
#include "engine/model/experiment.h"

namespace vesselid {

// Reads `node` (the value of input_noise at `path`) into spec->input_noise; spec->inputs
// already read. Fails with the file, line and key on an unknown or unmapped input, a sigma
// <= 0 or a spacing <= 0.
void ReadInputNoise(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                    const ModelInfo& info, ExperimentSpec* spec);

}  // namespace vesselid
