// The one number syntax of vesselid's inputs (CSV fields and YAML scalars): a decimal or
// exponent form as std::from_chars reads it, with at most one leading '+'. Subnormal values
// are numbers like any other; nan, inf, hexadecimal and surrounding spaces are not.
#pragma once

#include <string_view>

namespace vesselid {

// Parses the whole of `text` as a finite double into *value; false if it is not one.
bool ParseFiniteNumber(std::string_view text, double* value);

}  // namespace vesselid
