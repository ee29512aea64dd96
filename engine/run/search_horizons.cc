#include "engine/run/search_horizons.h"

#include <algorithm>
#include <limits>

namespace vesselid {

namespace {
constexpr double kFirstFraction = 1.0 / 6.0;  // of the shortest experiment
constexpr int kMinIntervals = 20;             // sample intervals of the first piece
constexpr double kGrowth = 3.0;               // from one phase to the next
}  // namespace

std::vector<double> AutomaticHorizons(const std::vector<Experiment>& experiments) {
  double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
  std::vector<double> intervals;
  for (const Experiment& e : experiments) {
    if (e.node_time.size() < 2) continue;
    const double duration = e.node_time.back() - e.node_time.front();
    shortest = std::min(shortest, duration);
    longest = std::max(longest, duration);
    intervals.push_back(duration / static_cast<double>(e.node_time.size() - 1));
  }
  if (intervals.empty()) return {};
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  const double interval = intervals[intervals.size() / 2];
  double length = std::max(kFirstFraction * shortest, kMinIntervals * interval);
  std::vector<double> lengths;
  if (length >= 0.5 * shortest) return lengths;
  for (; length < 0.5 * longest; length *= kGrowth) lengths.push_back(length);
  return lengths;
}

}  // namespace vesselid
