#include "engine/data/time_base.h"

#include <cstdio>
#include <ctime>
#include <limits>

namespace vesselid {

bool ParseNanoseconds(std::string_view text, std::int64_t* ns) {
  size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
  // The first 19 significant digits (they fit in 64 bits) as an integer scaled by 10^scale;
  // later ones are below 1 ns for any time this can hold, and are dropped.
  std::uint64_t digits = 0;
  int scale = 0, count = 0;
  bool any = false, point = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (c < '0' || c > '9') break;
    any = true;
    if (count < 19) {
      if (digits > 0 || c != '0') ++count;
      digits = digits * 10 + static_cast<std::uint64_t>(c - '0');
      if (point) --scale;
    } else if (!point) {
      ++scale;
    }
  }
  if (!any) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exponent_negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) exponent_negative = text[i++] == '-';
    if (i == text.size()) return false;
    int exponent = 0;
    for (; i < text.size(); ++i) {
      if (text[i] < '0' || text[i] > '9' || exponent > 1000) return false;
      exponent = exponent * 10 + (text[i] - '0');
    }
    scale += exponent_negative ? -exponent : exponent;
  }
  if (i != text.size()) return false;
  // digits * 10^(scale + 9) ns; digits below 1 ns rounded half away from zero.
  constexpr std::uint64_t kMax =
      static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  std::uint64_t value = digits;
  int shift = scale + 9;
  for (; shift > 0 && value != 0; --shift) {
    if (value > kMax / 10) return false;
    value *= 10;
  }
  int removed = 0;  // the most significant digit removed
  for (; shift < 0; ++shift) {
    removed = static_cast<int>(value % 10);
    value /= 10;
  }
  if (removed >= 5) ++value;
  if (value > kMax) return false;
  *ns = negative ? -static_cast<std::int64_t>(value) : static_cast<std::int64_t>(value);
  return true;
}

std::string FormatNanoseconds(std::int64_t ns) {
  const bool negative = ns < 0;
  const std::uint64_t magnitude =
      negative ? 0 - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  char text[48];
  std::snprintf(text, sizeof(text), "%s%llu.%09llu", negative ? "-" : "",
                static_cast<unsigned long long>(magnitude / 1000000000u),
                static_cast<unsigned long long>(magnitude % 1000000000u));
  std::string s = text;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string FormatUtc(std::int64_t ns) {
  std::int64_t seconds = ns / 1000000000;
  std::int64_t rest = ns % 1000000000;
  if (rest < 0) {
    rest += 1000000000;
    --seconds;
  }
  const std::time_t t = static_cast<std::time_t>(seconds);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[64];
  std::snprintf(text, sizeof(text), "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                static_cast<int>(rest / 1000000));
  return text;
}

}  // namespace vesselid
