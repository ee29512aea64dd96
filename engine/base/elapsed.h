// Wall time since a point, in seconds, for the timings stages and studies report.
#pragma once

#include <chrono>

namespace vesselid {

using SteadyClock = std::chrono::steady_clock;

inline double SecondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace vesselid
