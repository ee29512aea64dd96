// The keys of an experiment that prepare its raw columns (model/experiment_data.h):
//
//   time:     {column: t}                       the time column (epoch times automatic)
//   position: {lat: <col>, lon: <col>, origin: first | [lat, lon]}
//   screen:   {max_speed: m/s, max_rate: {<output>: per s}, stale: n, zero_fix: true}
//   resample: {rate: Hz, max_gap: 3}
#pragma once

#include <string>

#include "engine/config/yaml_reader.h"
#include "engine/model/experiment.h"

namespace vesselid {

// Reads the keys above from the experiment map `node` at `path` into spec (spec.outputs and
// spec.csv already read); fails with the file, line and key.
void ReadExperimentData(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                        const ModelInfo& info, ExperimentSpec* spec);

}  // namespace vesselid
