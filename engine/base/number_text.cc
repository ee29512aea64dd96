#include "engine/base/number_text.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace vesselid {
namespace {

// Whether a decimal text from_chars found out of range is below one in magnitude (an
// underflow, as 1e-999) rather than above the largest double (1e999): with p mantissa digits
// before the point and the first non-zero digit the k-th digit, that digit stands for
// 10^(p - 1 - k + exponent).
bool BelowOne(std::string_view text) {
  int digits = 0, before_point = -1, first_nonzero = -1;
  size_t i = 0;
  for (; i < text.size() && text[i] != 'e' && text[i] != 'E'; ++i) {
    if (text[i] == '.') before_point = digits;
    if (text[i] < '0' || text[i] > '9') continue;
    if (first_nonzero < 0 && text[i] != '0') first_nonzero = digits;
    ++digits;
  }
  if (first_nonzero < 0) return true;
  if (before_point < 0) before_point = digits;
  long exponent = 0;
  if (i + 1 < text.size()) {
    const char* from = text.data() + i + 1 + (text[i + 1] == '+');
    const auto [end, error] = std::from_chars(from, text.data() + text.size(), exponent);
    if (error == std::errc::result_out_of_range) return text[i + 1] == '-';
  }
  return before_point - 1 - first_nonzero + exponent < 0;
}

}  // namespace

bool ParseFiniteNumber(std::string_view text, double* value) {
  const char* first = text.data();
  const char* last = first + text.size();
  // from_chars takes a '-' but no '+': skip one '+', and not before a '-' ("+-1").
  if (first != last && *first == '+') {
    if (++first != last && *first == '-') return false;
  }
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(first, last, parsed);
  if (error == std::errc::result_out_of_range && end == last &&
      BelowOne(std::string_view(first, last - first))) {
    // Below the smallest subnormal double: the nearest double is zero, of the text's sign.
    *value = *first == '-' ? -0.0 : 0.0;
    return true;
  }
  if (error != std::errc() || end != last || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

}  // namespace vesselid
