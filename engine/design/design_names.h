// Small helpers the design files share: a name's index in a list, and the degree.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

inline constexpr double kDesignDegree = 3.14159265358979323846 / 180.0;  // rad

// The index of `name` in `names`, or -1.
inline int NameIndex(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace vesselid
