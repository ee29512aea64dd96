// A command's few output files published as one set (output_staging.h) into a folder that is
// checked and locked first (output_folder.h): `vesselid export`, `predict` and `design`.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vesselid {

// Writes a file at the path given; false with a message.
using FileWriter = std::function<bool(const std::string& path, std::string* error)>;

// `files` (name, writer) published as the set `set` into `out_dir`, none of them replacing
// `input`.
bool PublishSet(const std::string& out_dir, const std::string& set, const std::string& input,
                const std::vector<std::pair<std::string, FileWriter>>& files, std::string* error);

}  // namespace vesselid
