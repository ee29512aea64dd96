// results.json without what differs between two runs of the same config and data: every
// "time_seconds" and the wall times the notes end with (", 0.077 s"). Tests that require two
// runs to agree bit for bit compare what is left.
#pragma once

#include <regex>
#include <string>

#include "nlohmann/json.hpp"

namespace vesselid::testing {

inline void DropTimes(nlohmann::json* j) {
  if (j->is_string()) {
    static const std::regex kNoteTime(", [0-9]+\\.[0-9]{3} s($|[;,)])");
    *j = std::regex_replace(j->get<std::string>(), kNoteTime, ", <time> s$1");
  } else if (j->is_object()) {
    j->erase("time_seconds");
    for (auto& [key, value] : j->items()) DropTimes(&value);
  } else if (j->is_array()) {
    for (nlohmann::json& value : *j) DropTimes(&value);
  }
}

}  // namespace vesselid::testing
