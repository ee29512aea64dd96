#include "engine/run/zigzag_reflight.h"

#include <algorithm>
#include <cmath>

#include "engine/base/statistics.h"

namespace vesselid {
namespace {

// s: the longest step between two checks of the re-flown heading (the run's RK4 step can be
// a log interval of 1 s, and a check late by a step puts the rudder a second late).
constexpr double kCheckStep = 0.05;

}  // namespace

bool FindZigzagCommands(const std::vector<double>& t, const std::vector<double>& delta,
                        const std::vector<double>& psi, const ZigzagTest& test,
                        ZigzagCommands* commands, std::string* why) {
  double highest = -INFINITY, lowest = INFINITY;
  for (double d : delta) {
    if (!std::isfinite(d)) continue;
    highest = std::max(highest, d);
    lowest = std::min(lowest, d);
  }
  // Plateaus either side of the neutral: the samples beyond half of the way from the middle
  // of the range to each extreme (a rudder biased by a few degrees keeps both sides).
  const double middle = 0.5 * (highest + lowest), half = 0.5 * (highest - lowest);
  std::vector<double> upper, lower;
  for (double d : delta) {
    if (!std::isfinite(d)) continue;
    if (d > middle + 0.5 * half) upper.push_back(d);
    if (d < middle - 0.5 * half) lower.push_back(d);
  }
  if (upper.empty() || lower.empty() || !(half > 0.0)) {
    if (why != nullptr) *why = "the logged rudder has no plateau either side of its neutral";
    return false;
  }
  const double up = UpperMedian(upper), down = UpperMedian(lower);
  commands->neutral = 0.5 * (up + down);
  commands->amplitude = 0.5 * (up - down);
  // The first command: where the rudder stands, relative to the neutral, over the samples of
  // the first half-cycle after t_0 (to the first check, or 10 s where the record says less).
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < t.size() && i < delta.size(); ++i) {
    if (t[i] < test.first_execute || !std::isfinite(delta[i])) continue;
    if (t[i] > test.first_execute + 10.0 && count > 0) break;
    sum += delta[i] - commands->neutral;
    ++count;
  }
  commands->first_sign = sum >= 0.0 ? 1.0 : -1.0;
  // The checks, after t_0: where the rudder left each plateau. It counts as on a plateau
  // within a tenth of the amplitude (the log's noise); the moment it left is the ramp that
  // follows extrapolated back to the plateau (the first sample off it and the first 3 tenths
  // off: a rate-limited gear's straight line), and the check the heading change from psi_0
  // there, interpolated between samples.
  const double tolerance = 0.1 * commands->amplitude;
  const size_t n = std::min({t.size(), delta.size(), psi.size()});
  auto usable = [&](size_t i) {
    return t[i] >= test.first_execute && std::isfinite(delta[i]) && std::isfinite(psi[i]);
  };
  auto heading_at = [&](double when) {
    size_t i = 1;
    while (i + 1 < n && t[i] < when) ++i;
    const double w = std::clamp((when - t[i - 1]) / (t[i] - t[i - 1]), 0.0, 1.0);
    return psi[i - 1] + w * (psi[i] - psi[i - 1]);
  };
  // A record cut inside the zigzag (a window after the first execute) has no start to fly
  // from: its rudder stands on a plateau at its first sample.
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(delta[i])) continue;
    if (t[i] >= test.first_execute &&
        std::min(std::abs(delta[i] - up), std::abs(delta[i] - down)) <= tolerance) {
      if (why != nullptr) {
        *why = "the record starts inside the zigzag (its rudder already on a plateau): no "
               "start before the first execute to fly from";
      }
      return false;
    }
    break;
  }
  double psi0 = NAN;
  int on = 0;  // +1: on the upper plateau, -1: the lower, 0: neither
  std::vector<double> checks, slopes;
  for (size_t i = 0; i < n; ++i) {
    if (!usable(i)) continue;
    if (!std::isfinite(psi0)) psi0 = psi[i];
    const int now = std::abs(delta[i] - up) <= tolerance     ? 1
                    : std::abs(delta[i] - down) <= tolerance ? -1
                                                             : 0;
    if (on != 0 && now != on && i > 0) {
      const double level = on > 0 ? up : down;
      size_t j = i;
      while (j + 1 < n && usable(j + 1) && std::abs(delta[j] - level) < 3.0 * tolerance) ++j;
      // No sample on the ramp (a gear faster than the log): it left at the last sample on the
      // plateau and took at most one interval, half of one taken as the guess.
      const bool ramp = j > i && delta[j] != delta[i];
      const double slope = ramp ? (delta[j] - delta[i]) / (t[j] - t[i])
                                : (delta[i] - level) / (0.5 * (t[i] - t[i - 1]));
      if (slope != 0.0) slopes.push_back(std::abs(slope));
      const double left = ramp ? t[i] - (delta[i] - level) / slope : t[i - 1];
      checks.push_back(std::abs(heading_at(std::clamp(left, test.first_execute, t[i])) - psi0));
    }
    on = now;
  }
  if (checks.empty()) {
    if (why != nullptr) *why = "the logged rudder never leaves a plateau after the first execute";
    return false;
  }
  commands->check = UpperMedian(checks);
  commands->rate = UpperMedian(slopes);  // NaN without a ramp
  return true;
}

bool ReflyZigzag(const ModelHandle& model, const Experiment& experiment, const double* p,
                 const double* x0, const ZigzagTest& test, const ZigzagCommands& commands,
                 double rudder_rate, ZigzagReflight* reflight, std::string* why) {
  const ModelInfo& info = model.info();
  const int rudder = info.InputIndex("delta"), heading = info.OutputIndex("psi");
  if (rudder < 0 || heading < 0) {
    *why = "the model has no rudder input delta or heading output psi";
    return false;
  }
  const size_t nx = info.states.size(), nu = info.inputs.size();
  std::vector<double> x(x0, x0 + nx), k1(nx), k2(nx), k3(nx), k4(nx), xs(nx);
  std::vector<double> u0(nu), u_mid(nu), u1(nu), y(info.outputs.size());
  auto row = [&](size_t r, std::vector<double>* u) {
    std::copy_n(experiment.input_cache.begin() + r * nu, nu, u->begin());
  };
  auto heading_of = [&](const std::vector<double>& u) {
    model.Output(x.data(), u.data(), p, y.data());
    return y[heading];
  };
  *reflight = ZigzagReflight();
  row(0, &u0);
  reflight->t = {experiment.node_time.front()};
  reflight->psi = {heading_of(u0)};
  reflight->delta = {u0[rudder]};
  // The closed loop: command after t_0, the rudder where it stands, and the checks as
  // data/zigzag_figures.h and export/manoeuvres.cc define them.
  bool closed = false;
  double delta = 0.0, command = 0.0, psi0 = 0.0, sign = 0.0;
  const double plus = commands.neutral + commands.first_sign * commands.amplitude;
  const double minus = commands.neutral - commands.first_sign * commands.amplitude;
  auto moved = [&](double tau) {
    return delta + std::clamp(command - delta, -rudder_rate * tau, rudder_rate * tau);
  };
  // The run's RK4 step can be a whole log interval (1 s); the checks are timed on steps of at
  // most kCheckStep, the inputs between the step's start, midpoint and end rows linear.
  std::vector<double> a(nu), b(nu), c(nu);
  auto between = [&](double f, std::vector<double>* u) {  // f in [0, 1] of the run's step
    for (size_t i = 0; i < nu; ++i) {
      (*u)[i] = f <= 0.5 ? a[i] + 2.0 * f * (b[i] - a[i]) : b[i] + (2.0 * f - 1.0) * (c[i] - b[i]);
    }
  };
  size_t step = 0;
  for (int k = 0; k + 1 < experiment.num_nodes(); ++k) {
    const double run_step = experiment.node_step[k];
    const int pieces = std::max(1, static_cast<int>(std::ceil(run_step / kCheckStep - 1e-9)));
    const double h = run_step / pieces;
    for (int jj = 0; jj < experiment.node_substeps[k] * pieces; ++jj) {
      const int j = jj / pieces, piece = jj % pieces;
      if (piece == 0) {
        row(3 * step, &a);
        row(3 * step + 1, &b);
        row(3 * step + 2, &c);
        ++step;
      }
      const double start = experiment.node_time[k] + j * run_step + piece * h;
      between(static_cast<double>(piece) / pieces, &u0);
      between((piece + 0.5) / pieces, &u_mid);
      between(static_cast<double>(piece + 1) / pieces, &u1);
      if (!closed && start >= test.first_execute) {
        closed = true;
        delta = u0[rudder];
        command = plus;
        psi0 = reflight->psi.back();
      }
      if (closed) {
        u0[rudder] = delta;
        u_mid[rudder] = moved(0.5 * h);
        u1[rudder] = moved(h);
      }
      // RK4 as engine/model/rk4.h.
      bool ok = model.Derivative(x.data(), u0.data(), p, k1.data());
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k1[i];
      ok = ok && model.Derivative(xs.data(), u_mid.data(), p, k2.data());
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k2[i];
      ok = ok && model.Derivative(xs.data(), u_mid.data(), p, k3.data());
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + h * k3[i];
      ok = ok && model.Derivative(xs.data(), u1.data(), p, k4.data());
      for (size_t i = 0; i < nx; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
      const double now = heading_of(u1);
      if (!ok || !std::isfinite(now)) {
        *why = "the re-flown zigzag leaves finite numbers at t = " + std::to_string(start) + " s";
        return false;
      }
      reflight->t.push_back(start + h);
      reflight->psi.push_back(now);
      reflight->delta.push_back(u1[rudder]);
      if (!closed) continue;
      delta = u1[rudder];
      // The checks on the simulated heading change: the first either way sets the sign s,
      // then the rudder is reversed at s dpsi <= -check and s dpsi >= check in turn.
      const double change = now - psi0;
      const int n = reflight->reversals;
      if (n == 0 && std::abs(change) >= commands.check) {
        sign = change > 0.0 ? 1.0 : -1.0;
        command = minus;
        ++reflight->reversals;
      } else if (n % 2 == 1 && sign * change <= -commands.check) {
        command = plus;
        ++reflight->reversals;
      } else if (n > 0 && n % 2 == 0 && sign * change >= commands.check) {
        command = minus;
        ++reflight->reversals;
      }
    }
  }
  if (!closed) {
    *why = "the record ends before its first execute";
    return false;
  }
  ZigzagTest flown = test;
  flown.sign = sign != 0.0 ? sign : test.sign;
  flown.reversals = reflight->reversals;
  if (reflight->reversals > 0) reflight->figures = MeasureZigzag(reflight->t, reflight->psi, flown);
  return true;
}

}  // namespace vesselid
