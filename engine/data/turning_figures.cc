#include "engine/data/turning_figures.h"

#include <cmath>

namespace vesselid {
namespace {

constexpr double kMinTurningRudder = 5.0 * M_PI / 180.0;

bool Finite(double a, double b, double c) {
  return std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
}

}  // namespace

bool DetectTurningCircle(const std::vector<double>& t, const std::vector<double>& delta,
                         const std::vector<double>& psi, TurningTest* test, std::string* why) {
  auto fail = [&](const std::string& reason) {
    if (why != nullptr) *why = reason;
    return false;
  };
  const size_t n = t.size();
  if (delta.size() != n || psi.size() != n) return fail("columns of unequal length");
  double first = std::nan("");
  for (size_t k = 0; k < n && std::isnan(first); ++k) {
    if (Finite(t[k], delta[k], psi[k])) first = delta[k];
  }
  if (std::isnan(first)) return fail("no samples");
  double largest = 0.0;
  for (size_t k = 0; k < n; ++k) {
    if (Finite(t[k], delta[k], psi[k]) && std::abs(delta[k] - first) > std::abs(largest)) {
      largest = delta[k] - first;
    }
  }
  if (std::abs(largest) < kMinTurningRudder) return fail("the rudder moves less than 5 deg");
  const double side = largest > 0 ? 1.0 : -1.0;
  bool executed = false, held = false;
  double psi_0 = 0.0, turned = 0.0, heading_sign = 0.0;
  for (size_t k = 0; k < n; ++k) {
    if (!Finite(t[k], delta[k], psi[k])) continue;
    const double moved = side * (delta[k] - first);
    if (!executed && moved >= 0.1 * std::abs(largest)) {
      executed = true;
      test->execute = t[k];
      psi_0 = psi[k];
    }
    if (executed && moved >= 0.9 * std::abs(largest)) held = true;
    if (held && moved < 0.5 * std::abs(largest)) return fail("the rudder is not held");
    if (executed) {
      const double change = psi[k] - psi_0;
      if (std::abs(change) > std::abs(turned)) turned = change;
    }
  }
  if (std::abs(turned) < M_PI / 2) return fail("the heading turns less than 90 deg");
  heading_sign = turned > 0 ? 1.0 : -1.0;
  test->rudder = largest;
  test->sign = heading_sign;
  return true;
}

TurningFigures MeasureTurningCircle(const std::vector<double>& t, const std::vector<double>& x,
                                    const std::vector<double>& y, const std::vector<double>& psi,
                                    const TurningTest& test) {
  TurningFigures f;
  const size_t n = t.size();
  if (x.size() != n || y.size() != n || psi.size() != n) return f;
  bool started = false;
  double x0 = 0, y0 = 0, psi0 = 0, t_prev = 0, x_prev = 0, y_prev = 0, change_prev = 0;
  // The position and time where the heading change crosses `target`, between two samples.
  auto at = [&](double target, double tk, double xk, double yk, double change, double* time,
                double* xa, double* ya) {
    const double w = (target - change_prev) / (change - change_prev);
    *time = t_prev + w * (tk - t_prev);
    *xa = x_prev + w * (xk - x_prev);
    *ya = y_prev + w * (yk - y_prev);
  };
  for (size_t k = 0; k < n; ++k) {
    if (!Finite(t[k], x[k], y[k]) || !std::isfinite(psi[k]) || t[k] < test.execute) continue;
    const double change = test.sign * (psi[k] - psi0);
    if (!started) {
      started = true;
      x0 = x[k];
      y0 = y[k];
      psi0 = psi[k];
    } else {
      const double c = std::cos(psi0), s = std::sin(psi0);
      double time, xa, ya;
      if (std::isnan(f.time_to_90) && change >= M_PI / 2 && change_prev < M_PI / 2) {
        at(M_PI / 2, t[k], x[k], y[k], change, &time, &xa, &ya);
        f.time_to_90 = time - test.execute;
        f.advance = (xa - x0) * c + (ya - y0) * s;
        f.transfer = std::abs(-(xa - x0) * s + (ya - y0) * c);
      }
      if (std::isnan(f.time_to_180) && change >= M_PI && change_prev < M_PI) {
        at(M_PI, t[k], x[k], y[k], change, &time, &xa, &ya);
        f.time_to_180 = time - test.execute;
        f.tactical_diameter = std::abs(-(xa - x0) * s + (ya - y0) * c);
        break;
      }
    }
    t_prev = t[k];
    x_prev = x[k];
    y_prev = y[k];
    change_prev = started ? test.sign * (psi[k] - psi0) : 0.0;
  }
  return f;
}

}  // namespace vesselid
