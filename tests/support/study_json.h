// study.json as two equal studies must agree on it: without timings and process layout.
#pragma once

#include "nlohmann/json.hpp"

namespace vesselid::testing {

inline nlohmann::json ComparableStudy(nlohmann::json j) {
  if (j.is_object()) {
    for (const char* key :
         {"time_seconds", "mean_time_seconds", "processes", "threads_per_process"}) {
      j.erase(key);
    }
    for (auto& item : j.items()) item.value() = ComparableStudy(item.value());
  } else if (j.is_array()) {
    for (auto& item : j) item = ComparableStudy(item);
  }
  return j;
}

}  // namespace vesselid::testing
