// YAML merge keys (`<<: *defaults`, `<<: [*a, *b]`), which yaml-cpp 0.7 reads as a plain key
// named "<<". Resolved in place after the duplicate-key check and before any key check: the
// map takes every key of the merged maps that it does not give itself, in the place of the
// `<<` line; of several merged maps the earlier one wins (YAML 1.1 merge type). A quoted
// "<<" is an ordinary key.
#pragma once

#include "engine/config/yaml_reader.h"

namespace vesselid {

// Every map of `root` and below; a merge key whose value is not a map or a list of maps, or a
// map merging a map that contains it, is an error naming the file, line and key.
void ResolveMergeKeys(const YamlReader& reader, const YAML::Node& root);

}  // namespace vesselid
