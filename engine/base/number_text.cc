#include "engine/base/number_text.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace vesselid {

bool ParseFiniteNumber(std::string_view text, double* value) {
  const char* first = text.data();
  const char* last = first + text.size();
  // from_chars takes a '-' but no '+': skip one '+', and not before a '-' ("+-1").
  if (first != last && *first == '+') {
    if (++first != last && *first == '-') return false;
  }
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(first, last, parsed);
  if (error != std::errc() || end != last || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

}  // namespace vesselid
