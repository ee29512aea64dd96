// Numbers into message text: printf-style formatting of up to four doubles into a string
// (messages and report lines; not for data files, which use number_text.h).
#pragma once

#include <cstdio>
#include <string>

namespace vesselid {

inline std::string FormatNumbers(const char* format, double a, double b = 0.0, double c = 0.0,
                                 double d = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b, c, d);
  return text;
}

}  // namespace vesselid
