// Numbers into message text: printf-style formatting of up to four doubles into a string
// (messages and report lines; not for data files, which use number_text.h).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace vesselid {

inline std::string FormatNumbers(const char* format, double a, double b = 0.0, double c = 0.0,
                                 double d = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b, c, d);
  return text;
}

// One number by `format`, or "-" when it is not finite (table cells).
inline std::string FormatFinite(const char* format, double value) {
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

}  // namespace vesselid
