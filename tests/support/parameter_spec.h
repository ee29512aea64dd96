// A bounded parameter spec in one line, for tests that build problems directly.
#pragma once

#include <string>

#include "engine/solve/parameter.h"

namespace vesselid {
namespace testing {

inline ParameterSpec BoundedSpec(const std::string& name, double start, double lower,
                                 double upper) {
  ParameterSpec s;
  s.name = name;
  s.start = start;
  s.lower = lower;
  s.upper = upper;
  return s;
}

}  // namespace testing
}  // namespace vesselid
