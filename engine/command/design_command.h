// `vesselid design` as one call, for the command line and Python alike: the config's design
// section planned from a finished run, its files published into out_dir (default
// <run>/design) when `write`.
#pragma once

#include <string>

#include "engine/config/model_registry.h"
#include "engine/design/design_options.h"
#include "engine/design/design_result.h"

namespace vesselid {

// `config` (a path) or `text` (its YAML, named by config) holds the design section;
// `threads` > 0 replaces design.search.threads. False with a message naming file and key
// (*config_error: the config is at fault).
bool DesignCommand(const ModelRegistry& registry, const std::string& config,
                   const std::string& text, const std::string& run_dir, int threads, bool write,
                   const std::string& out_dir, DesignResult* result, std::string* error,
                   bool* config_error = nullptr);

}  // namespace vesselid
