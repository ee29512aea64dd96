// The version of vesselid: results.json's vesselid_version, `vesselid --version` and Python's
// vesselid.__version__. CMakeLists.txt checks it against the project's VERSION.
#pragma once

namespace vesselid {

inline constexpr char kVersion[] = "0.1.0";

}  // namespace vesselid
