// The one number syntax of vesselid's inputs (CSV fields and YAML scalars): a decimal or
// exponent form as std::from_chars reads it, with at most one leading '+'. Subnormal values
// are numbers like any other, and a value below the smallest subnormal (1e-999) is zero of its
// sign, the nearest double; one beyond the largest double (1e999), nan, inf, hexadecimal and
// surrounding spaces are not numbers.
#pragma once

#include <string_view>

namespace vesselid {

// Parses the whole of `text` as a finite double into *value; false if it is not one.
bool ParseFiniteNumber(std::string_view text, double* value);

}  // namespace vesselid
