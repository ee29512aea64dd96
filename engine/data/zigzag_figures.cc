#include "engine/data/zigzag_figures.h"

#include <algorithm>
#include <cmath>

#include "engine/base/statistics.h"

namespace vesselid {
namespace {

constexpr double kPlateauShare = 0.5;     // |delta| above this share of its largest: a plateau
constexpr double kLeaveShare = 0.1;       // the rudder has left a plateau by this share of delta_z
constexpr double kHoldShare = 0.8;        // 80 % of the plateau samples above this x delta_z
constexpr double kCheckTolerance = 0.25;  // heading changes at the reversals within 25 %
constexpr double kSmallestCheck = 0.5 * M_PI / 180.0;

// The finite value of `psi` nearest to index i (searching both ways); NaN if none.
double NearestFinite(const std::vector<double>& psi, size_t i) {
  for (size_t d = 0; d < psi.size(); ++d) {
    if (i >= d && std::isfinite(psi[i - d])) return psi[i - d];
    if (i + d < psi.size() && std::isfinite(psi[i + d])) return psi[i + d];
  }
  return std::nan("");
}

}  // namespace

bool DetectZigzag(const std::vector<double>& t, const std::vector<double>& delta,
                  const std::vector<double>& psi, ZigzagTest* test, std::string* why) {
  auto fail = [why](const std::string& reason) {
    if (why != nullptr) *why = reason;
    return false;
  };
  std::vector<size_t> valid;
  double largest = 0.0;
  for (size_t i = 0; i < t.size() && i < delta.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(delta[i])) continue;
    valid.push_back(i);
    largest = std::max(largest, std::abs(delta[i]));
  }
  if (valid.size() < 3 || !(largest > 0.0)) return fail("no rudder deflection");
  std::vector<double> plateau;
  for (size_t i : valid) {
    if (std::abs(delta[i]) >= kPlateauShare * largest) plateau.push_back(std::abs(delta[i]));
  }
  std::sort(plateau.begin(), plateau.end());
  const double rudder = SortedMedian(plateau);
  // Held, not swept: most plateau samples sit at delta_z (a sine's spread down to half).
  if (plateau[plateau.size() / 5] < kHoldShare * rudder) return fail("the rudder is not held");
  // Plateau sides in order: the first one's start, then each reversal's first sample.
  std::vector<size_t> sides;
  double side = 0.0;
  for (size_t i : valid) {
    if (std::abs(delta[i]) < kPlateauShare * rudder) continue;
    const double s = delta[i] > 0 ? 1.0 : -1.0;
    if (s != side) sides.push_back(i);
    side = s;
  }
  if (sides.size() < 3) return fail("the rudder reverses fewer than twice");
  // t_0: where the rudder left its initial value for the first plateau.
  double first_execute = t[valid.front()];
  for (size_t k = 0; k < valid.size() && valid[k] < sides[0]; ++k) {
    if (std::abs(delta[valid[k]] - delta[valid.front()]) <= kLeaveShare * rudder) {
      first_execute = t[valid[k]];
    }
  }
  if (std::abs(delta[valid.front()]) >= kPlateauShare * rudder) first_execute = t[valid.front()];
  // Each reversal's execute: the last sample still on the old plateau.
  std::vector<size_t> executes;
  for (size_t r = 1; r < sides.size(); ++r) {
    const double old_side = delta[sides[r]] > 0 ? -1.0 : 1.0;
    size_t at = sides[r - 1];
    for (size_t i : valid) {
      if (i >= sides[r]) break;
      if (i >= sides[r - 1] && old_side * delta[i] >= (1.0 - kLeaveShare) * rudder) at = i;
    }
    executes.push_back(at);
  }
  size_t start = 0;
  while (start < t.size() && t[start] < first_execute) ++start;
  const double psi0 = NearestFinite(psi, start);
  if (!std::isfinite(psi0)) return fail("no heading");
  std::vector<double> changes, sizes;
  for (size_t at : executes) {
    changes.push_back(NearestFinite(psi, at) - psi0);
    sizes.push_back(std::abs(changes.back()));
  }
  const double check = Median(sizes);
  if (!(check >= kSmallestCheck)) return fail("the heading hardly changes at the reversals");
  for (size_t k = 0; k < changes.size(); ++k) {
    const bool alternates = k == 0 || changes[k] * changes[k - 1] < 0.0;
    if (!alternates || std::abs(sizes[k] - check) > kCheckTolerance * check) {
      return fail("the rudder reversals do not follow the heading checks");
    }
  }
  test->rudder = rudder;
  test->heading = check;
  test->first_execute = first_execute;
  test->sign = changes[0] > 0 ? 1.0 : -1.0;
  test->reversals = static_cast<int>(executes.size());
  return true;
}

ZigzagFigures MeasureZigzag(const std::vector<double>& t, const std::vector<double>& psi,
                            const ZigzagTest& test) {
  ZigzagFigures f;
  std::vector<size_t> valid;
  for (size_t i = 0; i < t.size() && i < psi.size(); ++i) {
    if (std::isfinite(t[i]) && std::isfinite(psi[i]) && t[i] >= test.first_execute) {
      valid.push_back(i);
    }
  }
  if (valid.empty()) return f;
  const double psi0 = psi[valid.front()];
  const double z = test.heading;
  auto change = [&](size_t i) { return test.sign * (psi[i] - psi0); };
  f.executes.push_back(test.first_execute);
  std::vector<size_t> at;  // sample index of each execute after t_0
  double target = 1.0;
  for (size_t i : valid) {
    if (target * change(i) >= z) {
      f.executes.push_back(t[i]);
      at.push_back(i);
      target = -target;
    }
  }
  // Largest excess of direction x Dpsi beyond psi_z from execute `from` to the next one (or the
  // record's end, if the heading turned back before it).
  auto overshoot = [&](size_t from, double direction) {
    const size_t begin = at[from];
    const size_t end = from + 1 < at.size() ? at[from + 1] : valid.back();
    double best = -INFINITY;
    size_t best_at = begin;
    for (size_t i : valid) {
      if (i < begin || i > end) continue;
      if (direction * change(i) - z > best) {
        best = direction * change(i) - z;
        best_at = i;
      }
    }
    const bool turned_back = from + 1 < at.size() || best_at < valid.back();
    return turned_back ? best : ZigzagFigures::kUnknown;
  };
  if (!at.empty()) {
    f.time_to_first_check = f.executes[1] - f.executes[0];
    f.first_overshoot = overshoot(0, 1.0);
  }
  if (at.size() >= 2) f.second_overshoot = overshoot(1, -1.0);
  if (f.executes.size() >= 3) {
    double sum = 0.0;
    for (size_t k = 0; k + 2 < f.executes.size(); ++k) sum += f.executes[k + 2] - f.executes[k];
    f.period = sum / static_cast<double>(f.executes.size() - 2);
  }
  return f;
}

}  // namespace vesselid
