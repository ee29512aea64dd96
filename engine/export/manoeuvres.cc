#include "engine/export/manoeuvres.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <utility>

#include "engine/base/json_number.h"
#include "engine/base/parallel_for.h"
#include "engine/data/zigzag_figures.h"

namespace vesselid {
namespace {

constexpr double kNotPredicted = ManoeuvreConditions::kUnknown;
constexpr double kDegreeInRadians = 3.14159265358979323846 / 180.0;
// deg/s: a pull-out's residual yaw rate from which the ship counts as course-unstable (a
// stable ship's rate has decayed by then to a small fraction of this; an unstable one keeps a
// turn of tenths of a degree per second).
constexpr double kResidualRate = 0.01;

// Where the rudder, the speed and the heading are in the model.
struct Layout {
  int delta = -1, speed = -1, psi = -1;
};

int IndexOf(const std::vector<ModelVariable>& list, const std::string& name) {
  for (size_t i = 0; i < list.size(); ++i) {
    if (list[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// The identified process noise flown in one member (process_noise.h): after each RK4 step of
// length h, state i moves by sqrt(q_i h) N(0, 1), Euler-Maruyama's increment of
// dx_i = f_i dt + sqrt(q_i) dW_i with the drift f by RK4. Null: the calm the estimate flies in.
struct Gusts {
  std::vector<std::pair<int, double>> states;  // (state index, q)
  std::mt19937_64 random;
  std::normal_distribution<double> normal;
};

// The heading (rad) every step h of a manoeuvre with parameters p from a straight course
// (every state zero) at `speed`: the rudder follows `command(time, heading change)` at the steering
// gear's rate; `done()` true ends it early. False where the model refuses or the
// heading stops being finite; t and psi hold what was reached.
template <class Command, class Done>
bool Steer(const ModelHandle& model, const Layout& layout, double speed,
           const std::vector<double>& p, const ManoeuvreConditions& c, double h, double duration,
           Command&& command_of, Done&& done, Gusts* gusts, std::vector<double>* t,
           std::vector<double>* psi) {
  const ModelInfo& info = model.info();
  const size_t nx = info.states.size(), nu = info.inputs.size();
  std::vector<double> x(nx, 0.0), k1(nx), k2(nx), k3(nx), k4(nx), xs(nx), y(info.outputs.size());
  std::vector<double> u0(nu, kNotPredicted), u_mid(nu, kNotPredicted), u1(nu, kNotPredicted);
  for (std::vector<double>* u : {&u0, &u_mid, &u1}) {
    if (layout.speed >= 0) (*u)[layout.speed] = speed;
    (*u)[layout.delta] = 0.0;
  }
  auto heading_of = [&](const std::vector<double>& state, const std::vector<double>& u) {
    model.Output(state.data(), u.data(), p.data(), y.data());
    return y[layout.psi];
  };
  const double psi0 = heading_of(x, u0);
  double delta = 0.0, command = command_of(0.0, 0.0);
  *t = {0.0};
  *psi = {psi0};
  auto moved = [&](double tau) {
    return delta + std::clamp(command - delta, -c.rudder_rate * tau, c.rudder_rate * tau);
  };
  for (double time = 0.0; time < duration && !done(); time += h) {
    u0[layout.delta] = delta;
    u_mid[layout.delta] = moved(0.5 * h);
    u1[layout.delta] = moved(h);
    // RK4 as engine/model/rk4.h.
    if (!model.Derivative(x.data(), u0.data(), p.data(), k1.data())) return false;
    for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k1[i];
    if (!model.Derivative(xs.data(), u_mid.data(), p.data(), k2.data())) return false;
    for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k2[i];
    if (!model.Derivative(xs.data(), u_mid.data(), p.data(), k3.data())) return false;
    for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + h * k3[i];
    if (!model.Derivative(xs.data(), u1.data(), p.data(), k4.data())) return false;
    for (size_t i = 0; i < nx; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    if (gusts != nullptr) {
      for (const auto& [i, q] : gusts->states) x[i] += std::sqrt(q * h) * gusts->normal(gusts->random);
    }
    delta = u1[layout.delta];
    const double now = heading_of(x, u1);
    if (!std::isfinite(now)) return false;
    t->push_back(time + h);
    psi->push_back(now);
    command = command_of(time + h, now - psi0);
  }
  return true;
}

// The figures of a delta_z / psi_z zigzag with parameters p: first and second overshoot
// (rad) and the time to the first check (s); NaN where the simulation does not reach them.
ZigzagFigures SimulateZigzag(const ModelHandle& model, const Layout& layout, double speed,
                             const std::vector<double>& p, double rudder, double heading,
                             const ManoeuvreConditions& c, Gusts* gusts) {
  // The checks: the first heading change of psi_z in either direction sets the sign s, then
  // the rudder is reversed at s dpsi >= psi_z and s dpsi <= -psi_z in turn.
  double command = rudder, sign = 0.0;
  int reversals = 0;
  auto command_of = [&](double, double change) {
    if (reversals == 0 && std::abs(change) >= heading) {
      sign = change > 0.0 ? 1.0 : -1.0;
      command = -rudder;
      ++reversals;
    } else if (reversals % 2 == 1 && sign * change <= -heading) {
      command = rudder;
      ++reversals;
    } else if (reversals > 0 && reversals % 2 == 0 && sign * change >= heading) {
      command = -rudder;
      ++reversals;
    }
    return command;
  };
  std::vector<double> t, psi;
  if (!Steer(
          model, layout, speed, p, c, c.step, c.duration, command_of,
          [&] { return reversals >= 4; }, gusts, &t, &psi) ||
      reversals == 0) {
    return ZigzagFigures();
  }
  ZigzagTest test;
  test.rudder = rudder;
  test.heading = heading;
  test.first_execute = 0.0;
  test.sign = sign;
  test.reversals = reversals;
  return MeasureZigzag(t, psi, test);
}

// The pull-out test (MSC/Circ.1053): a steady turn on `rudder` for c.pull_out_turn s, the
// rudder back to midships at the gear's rate, and the yaw rate left after c.pull_out_settle s
// (deg/s, the heading's mean rate over the last tenth), after a turn to either side: half
// their difference, |r_starboard - r_port| / 2, the spiral's loop. Zero: the ship is
// course-stable (a rudder bias turns it the same way after both, which is no instability); a
// residual rate: unstable, each turn kept on its own side. NaN where a simulation fails.
double PullOutResidualRate(const ModelHandle& model, const Layout& layout, double speed,
                           const std::vector<double>& p, double rudder,
                           const ManoeuvreConditions& c, Gusts* gusts) {
  double rates[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const double side = k == 0 ? rudder : -rudder;
    std::vector<double> t, psi;
    auto command_of = [&](double time, double) { return time < c.pull_out_turn ? side : 0.0; };
    if (!Steer(
            model, layout, speed, p, c, c.pull_out_step, c.pull_out_turn + c.pull_out_settle,
            command_of, [] { return false; }, gusts, &t, &psi)) {
      return kNotPredicted;
    }
    const size_t last = t.size() - 1, from = last - last / 10;
    rates[k] = (psi[last] - psi[from]) / (t[last] - t[from]) / kDegreeInRadians;
  }
  return 0.5 * std::abs(rates[0] - rates[1]);
}

// The figures a parameter vector predicts, in the order of `names` below; in the identified
// sea where `gusts` is given.
std::vector<double> FiguresOf(const ModelHandle& model, const Layout& layout, double speed,
                              double length, const std::vector<double>& p,
                              const ManoeuvreConditions& c, Gusts* gusts = nullptr) {
  const ZigzagFigures ten = SimulateZigzag(model, layout, speed, p, 10 * kDegreeInRadians,
                                           10 * kDegreeInRadians, c, gusts);
  const ZigzagFigures twenty = SimulateZigzag(model, layout, speed, p, 20 * kDegreeInRadians,
                                              20 * kDegreeInRadians, c, gusts);
  const double turning = std::isfinite(speed) && std::isfinite(length)
                             ? ten.time_to_first_check * speed / length
                             : ten.time_to_first_check;
  return {ten.first_overshoot / kDegreeInRadians,
          ten.second_overshoot / kDegreeInRadians,
          twenty.first_overshoot / kDegreeInRadians,
          twenty.second_overshoot / kDegreeInRadians,
          turning,
          PullOutResidualRate(model, layout, speed, p, 20 * kDegreeInRadians, c, gusts)};
}

std::string JoinList(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

std::string FormatG3(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

double Quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const double position = q * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - below) * (values[above] - values[below]);
}

// The IMO MSC.137(76) 5.4 criterion of figure `f` for L/U (s); NaN and "" when it has none.
double Criterion(int f, double l_over_u, std::string* text) {
  char buffer[160];
  switch (f) {
    case 0:  // 10/10 first overshoot
      if (l_over_u < 10.0) {
        *text = "<= 10 deg (L/U < 10 s)";
        return 10.0;
      }
      if (l_over_u >= 30.0) {
        *text = "<= 20 deg (L/U >= 30 s)";
        return 20.0;
      }
      std::snprintf(buffer, sizeof(buffer), "<= 5 + 0.5 L/U = %.1f deg (10 <= L/U = %.1f < 30 s)",
                    5.0 + 0.5 * l_over_u, l_over_u);
      *text = buffer;
      return 5.0 + 0.5 * l_over_u;
    case 1:  // 10/10 second overshoot
      if (l_over_u < 10.0) {
        *text = "<= 25 deg (L/U < 10 s)";
        return 25.0;
      }
      if (l_over_u >= 30.0) {
        *text = "<= 40 deg (L/U >= 30 s)";
        return 40.0;
      }
      std::snprintf(buffer, sizeof(buffer),
                    "<= 17.5 + 0.75 L/U = %.1f deg (10 <= L/U = %.1f < 30 s)",
                    17.5 + 0.75 * l_over_u, l_over_u);
      *text = buffer;
      return 17.5 + 0.75 * l_over_u;
    case 2:  // 20/20 first overshoot
      *text = "<= 25 deg";
      return 25.0;
    case 4:  // initial turning ability
      *text = "<= 2.5 ship lengths";
      return 2.5;
    default:
      *text = "";
      return kNotPredicted;
  }
}

}  // namespace

bool PredictManoeuvres(const IdentifiedModel& exported, const ModelHandle& model,
                       const ManoeuvreConditions& c, ManoeuvrePredictions* predictions,
                       std::string* error) {
  Layout layout;
  layout.delta = IndexOf(exported.inputs, "delta");
  layout.psi = IndexOf(exported.outputs, "psi");
  layout.speed = IndexOf(exported.inputs, "U");
  if (layout.delta < 0 || layout.psi < 0) {
    *error = "model " + exported.model +
             ": the standard manoeuvres need a rudder input 'delta' and a heading output 'psi'";
    return false;
  }
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < info.inputs.size(); ++i) {
    const int index = static_cast<int>(i);
    if (index == layout.delta || index == layout.speed || info.InputOptional(index)) continue;
    *error = "model " + exported.model + ": its input '" + info.inputs[i] +
             "' has no value in a standard manoeuvre";
    return false;
  }
  if (layout.speed >= 0 && !(c.speed > 0.0)) {
    *error = "model " + exported.model + " takes the speed U as an input: give it (--speed, m/s)";
    return false;
  }
  ManoeuvrePredictions out;
  out.length = c.length;
  out.speed = c.speed;
  const bool ship = std::isfinite(c.length) && std::isfinite(c.speed);
  const std::vector<std::string> names = {"zigzag_10_10.first_overshoot",
                                          "zigzag_10_10.second_overshoot",
                                          "zigzag_20_20.first_overshoot",
                                          "zigzag_20_20.second_overshoot",
                                          ship ? "initial_turning" : "initial_turning_time",
                                          "pull_out.residual_rate"};
  const std::vector<double> estimate =
      FiguresOf(model, layout, c.speed, c.length, exported.values, c);
  // Every member flies the manoeuvres on its own: on every core.
  std::vector<std::vector<double>> members(exported.ensemble.size());
  ParallelFor(static_cast<int>(members.size()), 0, [&](int k) {
    members[k] = FiguresOf(model, layout, c.speed, c.length, exported.ensemble[k], c);
  });
  // The same members in the identified sea, each with its own gusts: seeded by the ensemble's
  // seed and the member's index, so the interval is the same on any number of cores.
  for (const ProcessNoise& noise : exported.process_noise) {
    char value[40];
    std::snprintf(value, sizeof(value), "%.6g", noise.spectral_density);
    const std::string named = "process noise q.process." + noise.state + " = " + value;
    if (info.StateIndex(noise.state) < 0) {
      out.notes.push_back(named + " not flown: model " + exported.model + " has no state '" +
                          noise.state + "' (" + JoinList(info.states) + ")");
    } else if (!(noise.spectral_density > 0.0) || !std::isfinite(noise.spectral_density)) {
      out.notes.push_back(named + " not flown: a spectral density is positive and finite");
    } else if (std::any_of(out.process_noise.begin(), out.process_noise.end(),
                           [&](const ProcessNoise& n) { return n.state == noise.state; })) {
      out.notes.push_back(named + " not flown: the state's process noise is listed twice (the "
                          "first is flown)");
    } else {
      out.process_noise.push_back(noise);
    }
  }
  std::vector<std::vector<double>> in_sea;
  if (!out.process_noise.empty()) {
    std::vector<std::pair<int, double>> states;
    for (const ProcessNoise& noise : out.process_noise) {
      states.emplace_back(info.StateIndex(noise.state), noise.spectral_density);
    }
    in_sea.resize(exported.ensemble.size());
    ParallelFor(static_cast<int>(in_sea.size()), 0, [&](int k) {
      Gusts gusts{states,
                  std::mt19937_64(static_cast<std::uint64_t>(exported.ensemble_seed) * 1000003u +
                                  static_cast<std::uint64_t>(k) + 1u),
                  std::normal_distribution<double>()};
      in_sea[k] = FiguresOf(model, layout, c.speed, c.length, exported.ensemble[k], c, &gusts);
    });
  }
  // Delta method: J by central differences of one standard error each side.
  const int n = static_cast<int>(exported.covariance_names.size());
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(names.size(), n);
  for (int a = 0; a < n; ++a) {
    const int i = IndexOf(exported.parameters, exported.covariance_names[a]);
    const double se = std::sqrt(std::max(exported.covariance(a, a), 0.0));
    if (i < 0 || !(se > 0.0)) continue;
    std::vector<double> up = exported.values, down = exported.values;
    up[i] += se;
    down[i] -= se;
    const std::vector<double> f_up = FiguresOf(model, layout, c.speed, c.length, up, c);
    const std::vector<double> f_down = FiguresOf(model, layout, c.speed, c.length, down, c);
    for (size_t f = 0; f < names.size(); ++f) jacobian(f, a) = (f_up[f] - f_down[f]) / (2.0 * se);
  }
  const Eigen::MatrixXd variance = jacobian * exported.covariance * jacobian.transpose();
  const double l_over_u = ship ? c.length / c.speed : kNotPredicted;
  for (size_t f = 0; f < names.size(); ++f) {
    ManoeuvreFigure figure;
    figure.name = names[f];
    figure.unit = f < 4 ? "deg" : f == 5 ? "deg/s" : ship ? "ship lengths" : "s";
    figure.value = estimate[f];
    std::vector<double> values;
    for (const std::vector<double>& m : members) {
      if (std::isfinite(m[f])) values.push_back(m[f]);
    }
    figure.members = static_cast<int>(values.size());
    if (!values.empty()) {
      figure.ensemble_low = Quantile(values, 0.025);
      figure.ensemble_high = Quantile(values, 0.975);
    }
    std::vector<double> sea;
    for (const std::vector<double>& m : in_sea) {
      if (std::isfinite(m[f])) sea.push_back(m[f]);
    }
    figure.disturbance_members = static_cast<int>(sea.size());
    if (!sea.empty()) {
      figure.disturbance_low = Quantile(sea, 0.025);
      figure.disturbance_high = Quantile(sea, 0.975);
    }
    if (!in_sea.empty() && sea.size() < in_sea.size() && std::isfinite(figure.value)) {
      out.notes.push_back(figure.name + " with disturbance: " +
                          std::to_string(in_sea.size() - sea.size()) + " of " +
                          std::to_string(in_sea.size()) +
                          " members did not reach it in their gusts (the heading did not turn "
                          "back, or the simulation diverged): the interval is of the others");
    }
    const double half = 1.96 * std::sqrt(std::max(variance(f, f), 0.0));
    if (std::isfinite(figure.value) && std::isfinite(half)) {
      figure.delta_low = figure.value - half;
      figure.delta_high = figure.value + half;
      const double ensemble_half = 0.5 * (figure.ensemble_high - figure.ensemble_low);
      // Both of no width (a figure no parameter moves, a stable ship's pull-out) agree too.
      figure.agree = (ensemble_half == 0.0 && half == 0.0) ||
                     (ensemble_half > 0.0 && half > 0.0 && half / ensemble_half <= 1.5 &&
                      ensemble_half / half <= 1.5);
    }
    // The L/U criteria need L and U; the 20/20 zigzag's does not.
    if (ship || f == 2) figure.limit = Criterion(static_cast<int>(f), l_over_u, &figure.criterion);
    if (std::isfinite(figure.limit)) {
      figure.meets = figure.value <= figure.limit;
      figure.interval_meets = figure.ensemble_high <= figure.limit;
    }
    if (!std::isfinite(figure.value)) {
      out.notes.push_back(figure.name + ": not reached within " +
                          std::to_string(static_cast<int>(c.duration)) +
                          " s (the heading does not turn back, or the simulation diverges)");
    }
    out.figures.push_back(figure);
  }
  // Course stability from the pull-out's residual rate over the ensemble.
  const ManoeuvreFigure& pull_out = out.figures.back();
  if (std::isfinite(pull_out.value)) {
    char text[300];
    // Over the ensemble's interval where there is one, else the estimate's value.
    const bool ensemble = pull_out.members > 0;
    const double low = ensemble ? pull_out.ensemble_low : pull_out.value;
    const double high = ensemble ? pull_out.ensemble_high : pull_out.value;
    const std::string every = ensemble ? ", with every member of the ensemble" : "";
    std::snprintf(text, sizeof(text),
                  "pull-out: %.3g deg/s of yaw rate left %.0f s after the rudder returned to "
                  "midships from a 20 deg turn: %s",
                  pull_out.value, c.pull_out_settle,
                  low >= kResidualRate
                      ? ("course-unstable (the spiral test would show a loop)" + every).c_str()
                  : high < kResidualRate
                      ? ("course-stable" + every).c_str()
                      : "the ensemble holds course-stable and course-unstable models");
    out.notes.push_back(text);
  }
  if (!out.process_noise.empty()) {
    std::string flown;
    for (const ProcessNoise& noise : out.process_noise) {
      char text[160];
      std::snprintf(text, sizeof(text), "%s%s's equation, q %.3g", flown.empty() ? "" : "; ",
                    noise.state.c_str(), noise.spectral_density);
      flown += text;
    }
    out.notes.push_back(
        "with disturbance: every member flown again in its own realisation of the process noise "
        "identified with the ship (" + flown +
        ", in the state's unit^2/s): where a trial in that sea would fall; the ensemble "
        "interval is the model's uncertainty alone, and the IMO criteria and the course "
        "stability are held against it (in gusts the pull-out's rate left is the gusts' turn "
        "as much as the ship's). The sensors' noise does not move the ship and is not flown");
  }
  if (!exported.ensemble.empty() && exported.ensemble.size() < 40) {
    out.notes.push_back(
        "the 95 % intervals are the 2.5 and 97.5 percentiles of " +
        std::to_string(exported.ensemble.size()) +
        " members: fewer than 40 place them between the extreme members, roughly (--members, "
        "100 by default)");
  }
  if (!ship) {
    out.notes.push_back(
        "the ship's length and speed are not known (--length, --speed): the initial turning "
        "ability is given as a time and the overshoots are held against no L/U criterion");
  }
  *predictions = std::move(out);
  return true;
}

std::string ManoeuvresText(const ManoeuvrePredictions& p) {
  std::string text = "standard manoeuvres (IMO MSC.137(76)), 95 % intervals";
  char line[400];
  if (std::isfinite(p.length) && std::isfinite(p.speed)) {
    std::snprintf(line, sizeof(line), " for L = %.4g m, U = %.4g m/s (L/U = %.3g s)", p.length,
                  p.speed, p.length / p.speed);
    text += line;
  }
  text += "\n";
  const bool sea = !p.process_noise.empty();
  std::snprintf(line, sizeof(line), "  %-30s %10s %-13s %23s %23s %7s%s  %s\n", "figure", "value",
                "unit", "ensemble 2.5-97.5 %", "delta method", "agree",
                sea ? "      with disturbance" : "", "IMO criterion");
  text += line;
  for (const ManoeuvreFigure& f : p.figures) {
    char ensemble[48], delta[48], disturbed[48] = "";
    std::snprintf(ensemble, sizeof(ensemble), "[%.3g, %.3g]", f.ensemble_low, f.ensemble_high);
    std::snprintf(delta, sizeof(delta), "[%.3g, %.3g]", f.delta_low, f.delta_high);
    if (sea) {
      std::snprintf(disturbed, sizeof(disturbed), " %22s",
                    ("[" + FormatG3(f.disturbance_low) + ", " + FormatG3(f.disturbance_high) + "]")
                        .c_str());
    }
    std::string verdict = f.criterion;
    if (std::isfinite(f.limit)) {
      verdict += f.meets ? (f.interval_meets ? ": met (the whole interval)"
                                             : ": met by the estimate, not by the whole interval")
                         : ": not met";
    }
    std::snprintf(line, sizeof(line), "  %-30s %10.4g %-13s %23s %23s %7s%s  %s\n", f.name.c_str(),
                  f.value, f.unit.c_str(), ensemble, delta, f.agree ? "yes" : "no", disturbed,
                  verdict.c_str());
    text += line;
  }
  for (const std::string& note : p.notes) text += "  note: " + note + "\n";
  return text;
}

nlohmann::json ManoeuvresToJson(const ManoeuvrePredictions& p) {
  nlohmann::json figures = nlohmann::json::array();
  for (const ManoeuvreFigure& f : p.figures) {
    figures.push_back(
        {{"name", f.name},
         {"unit", f.unit},
         {"value", JsonNumber(f.value)},
         {"ensemble_interval", {JsonNumber(f.ensemble_low), JsonNumber(f.ensemble_high)}},
         {"ensemble_members", f.members},
         {"delta_method_interval", {JsonNumber(f.delta_low), JsonNumber(f.delta_high)}},
         {"methods_agree", f.agree},
         {"criterion", f.criterion},
         {"limit", JsonNumber(f.limit)},
         {"meets", f.meets},
         {"interval_meets", f.interval_meets}});
    if (!p.process_noise.empty()) {
      figures.back()["disturbance_interval"] = {JsonNumber(f.disturbance_low),
                                                JsonNumber(f.disturbance_high)};
      figures.back()["disturbance_members"] = f.disturbance_members;
    }
  }
  nlohmann::json process_noise = nlohmann::json::array();
  for (const ProcessNoise& noise : p.process_noise) {
    process_noise.push_back({{"state", noise.state},
                             {"spectral_density", JsonNumber(noise.spectral_density)},
                             {"std_error", JsonNumber(noise.std_error)}});
  }
  return {{"length", JsonNumber(p.length)},
          {"speed", JsonNumber(p.speed)},
          {"figures", figures},
          {"process_noise", process_noise},
          {"notes", p.notes}};
}

}  // namespace vesselid
