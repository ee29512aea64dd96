// Time columns read without loss. A logger's Unix-epoch time (1.7e9 s with ms resolution)
// has a double spacing of 2.4e-7 s, so `t1 - t0` of two parsed doubles is off by up to
// that much; read as text into integer nanoseconds instead, t_k - t_0 is an exact integer
// and (t_k - t_0) / 1e9 the double nearest the true relative time (0.001 s apart stays
// exactly 0.001 apart).
//
// A record whose first time is at least kEpochThreshold seconds is an epoch log: its times
// are made relative to the first one (the origin, reported with the run).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vesselid {

// 1e8 s after 1970 is March 1973: no experiment clock counts that far from its own start.
inline constexpr double kEpochThreshold = 1e8;

// Parses a decimal number (`1700000000.123`, `-2.5`, `1.7e9`) exactly into nanoseconds,
// rounding digits below 1 ns half away from zero. False if the text is not such a number or
// its magnitude is beyond +-9.2e9 s.
bool ParseNanoseconds(std::string_view text, std::int64_t* ns);

// A time in seconds from nanoseconds as the nearest double to ns / 1e9.
inline double NanosecondsToSeconds(std::int64_t ns) { return static_cast<double>(ns) / 1e9; }

// "2023-11-14T22:13:20.123Z": an epoch time in UTC, to the millisecond.
std::string FormatUtc(std::int64_t ns);

// "1700000000.123": the exact decimal text of a time in nanoseconds, trailing zeros removed.
std::string FormatNanoseconds(std::int64_t ns);

}  // namespace vesselid
