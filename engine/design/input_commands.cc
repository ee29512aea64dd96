#include "engine/design/input_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "engine/design/design_names.h"

namespace vesselid {
namespace {

constexpr double kDesignPi = 3.14159265358979323846;

// The most levels a steps input may have: each is a variable of the search (NLopt's and the
// multistart's), and each evaluation simulates the plan; the shipped plans have 10-20.
constexpr int kMaxStepsPerInput = 256;

double Hold(const DesignInput& in, double duration) {
  return in.hold > 0.0 ? in.hold : duration / 12.0;
}

std::vector<double> Periods(const DesignInput& in, double duration) {
  if (!in.periods.empty()) return in.periods;
  std::vector<double> periods;
  for (double divisor : {1.0, 2.0, 3.0, 5.0, 8.0, 13.0}) periods.push_back(duration / divisor);
  return periods;
}

int VariableCount(const DesignInput& in, double duration) {
  switch (in.family) {
    case DesignInput::Family::kSteps:  // beyond the search's most, StepsFitTheSearch refuses
      return static_cast<int>(std::clamp(std::ceil(duration / Hold(in, duration) - 1e-9), 1.0,
                                         kMaxStepsPerInput + 1.0));
    case DesignInput::Family::kMultisine:
      return 2 * static_cast<int>(Periods(in, duration).size());
    case DesignInput::Family::kZigzag:
      return 2;
    case DesignInput::Family::kFixed:
      return 0;
  }
  return 0;
}

// The values every model input takes when it is not excited (NaN: an optional input not
// planned).
std::vector<double> Nominal(const DesignOptions& options, const DesignLayout& layout) {
  std::vector<double> value(layout.num_inputs, std::numeric_limits<double>::quiet_NaN());
  for (size_t d = 0; d < options.inputs.size(); ++d)
    value[layout.input[d]] = options.inputs[d].value;
  return value;
}

// Per zigzag: the first heading change of psi_z in either direction sets the sign s and
// reverses the rudder; then it is reversed at s dpsi <= -psi_z and s dpsi >= psi_z in turn.
struct ZigzagState {
  double rudder = 0.0, heading = 0.0, psi0 = 0.0, sign = 0.0, command = 0.0;
  bool started = false;
  double Next(double psi, int* reversals) {
    if (!started) {
      psi0 = psi;
      command = rudder;
      started = true;
    }
    const double change = psi - psi0;
    if (*reversals == 0 && std::abs(change) >= heading) {
      sign = change > 0.0 ? 1.0 : -1.0;
      command = -rudder;
      ++*reversals;
    } else if (*reversals % 2 == 1 && sign * change <= -heading) {
      command = rudder;
      ++*reversals;
    } else if (*reversals > 0 && *reversals % 2 == 0 && sign * change >= heading) {
      command = -rudder;
      ++*reversals;
    }
    return command;
  }
};

// A command that holds every input at its nominal value but those `set` changes.
Manoeuvre Holding(std::vector<double> nominal,
                  std::function<void(double, const double*, double*, int*)> set) {
  Manoeuvre m;
  auto reversals = m.reversals;
  m.command = [nominal, set, reversals](double t, const double* y, double* c) {
    std::copy(nominal.begin(), nominal.end(), c);
    set(t, y, c, reversals.get());
  };
  return m;
}

}  // namespace

bool StepsFitTheSearch(const DesignOptions& options, double duration, std::string* error) {
  for (const DesignInput& in : options.inputs) {
    if (in.family != DesignInput::Family::kSteps ||
        duration / Hold(in, duration) <= kMaxStepsPerInput) {
      continue;
    }
    char text[256];
    std::snprintf(text, sizeof(text),
                  ".hold: %.4g s over a %.4g s plan makes %.4g steps, more than the %d one "
                  "search can plan; hold each level at least %.4g s",
                  Hold(in, duration), duration, duration / Hold(in, duration), kMaxStepsPerInput,
                  duration / kMaxStepsPerInput);
    *error = "design.inputs." + in.name + text;
    return false;
  }
  return true;
}

bool MakeDesignLayout(const ModelInfo& info, const DesignOptions& options, double duration,
                      DesignLayout* layout, std::string* error) {
  DesignLayout out;
  out.duration = duration;
  out.num_inputs = static_cast<int>(info.inputs.size());
  out.rudder = NameIndex(info.inputs, "delta");
  out.heading = NameIndex(info.outputs, "psi");
  std::vector<bool> planned(info.inputs.size(), false);
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    const DesignInput& in = options.inputs[d];
    const std::string key = "design.inputs." + in.name;
    const int index = NameIndex(info.inputs, in.name);
    if (index < 0) {
      *error = key + ": the model has no input '" + in.name + "'";
      return false;
    }
    if (planned[index]) {
      *error = key + ": planned twice";
      return false;
    }
    planned[index] = true;
    if (in.family != DesignInput::Family::kFixed && !(in.lower < in.upper)) {
      *error = key + ": needs lower < upper";
      return false;
    }
    if (in.family != DesignInput::Family::kFixed && (in.value < in.lower || in.value > in.upper)) {
      *error = key + ".value: outside [lower, upper]";
      return false;
    }
    if (in.family == DesignInput::Family::kZigzag &&
        (index != out.rudder || out.heading < 0 ||
         !(in.headings.first > 0.0 && in.headings.first <= in.headings.second))) {
      *error = key +
               ": a zigzag steers the rudder 'delta' on the heading output 'psi', with "
               "headings: [lowest, highest] > 0";
      return false;
    }
    out.input.push_back(index);
    out.first.push_back(out.variables);
    out.count.push_back(VariableCount(in, duration));
    out.variables += out.count.back();
  }
  for (size_t i = 0; i < info.inputs.size(); ++i) {
    if (!planned[i] && !info.InputOptional(static_cast<int>(i))) {
      *error = "design.inputs: the model's input '" + info.inputs[i] +
               "' is not planned (give it a family, or `fixed` with its value)";
      return false;
    }
  }
  if (out.variables == 0) {
    *error = "design.inputs: every input is fixed; nothing to plan";
    return false;
  }
  *layout = out;
  return true;
}

Actuators MakeActuators(const ModelInfo& info, const DesignOptions& options,
                        const DesignLayout& layout) {
  const size_t nu = info.inputs.size();
  Actuators a;
  a.lower.assign(nu, -INFINITY);
  a.upper.assign(nu, INFINITY);
  a.rate.assign(nu, 0.0);
  a.start.assign(nu, std::numeric_limits<double>::quiet_NaN());
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    const DesignInput& in = options.inputs[d];
    const int i = layout.input[d];
    a.start[i] = in.value;
    if (in.family == DesignInput::Family::kFixed) {
      a.lower[i] = a.upper[i] = in.value;
    } else {
      a.lower[i] = in.lower;
      a.upper[i] = in.upper;
      a.rate[i] = in.rate;
    }
  }
  return a;
}

std::vector<double> QuietDesign(const DesignOptions& options, const DesignLayout& layout) {
  std::vector<double> z(layout.variables, 0.0);
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    const DesignInput& in = options.inputs[d];
    if (in.family != DesignInput::Family::kSteps) continue;  // amplitudes and rudder 0
    for (int j = 0; j < layout.count[d]; ++j) {
      z[layout.first[d] + j] = (in.value - in.lower) / (in.upper - in.lower);
    }
  }
  return z;
}

Manoeuvre CommandOf(const DesignOptions& options, const DesignLayout& layout,
                    const std::vector<double>& z) {
  const std::vector<double> nominal = Nominal(options, layout);
  // Each designed input's command from its share of z.
  std::vector<std::function<double(double, const double*, int*)>> parts;
  auto zigzag = std::make_shared<ZigzagState>();
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    const DesignInput& in = options.inputs[d];
    const double* v = z.data() + layout.first[d];
    const int count = layout.count[d];
    switch (in.family) {
      case DesignInput::Family::kSteps: {
        std::vector<double> levels(count);
        for (int j = 0; j < count; ++j) levels[j] = in.lower + v[j] * (in.upper - in.lower);
        const double hold = Hold(in, layout.duration);
        parts.push_back([levels, hold](double t, const double*, int*) {
          const int j = std::min(static_cast<int>(t / hold), static_cast<int>(levels.size()) - 1);
          return levels[j];
        });
        break;
      }
      case DesignInput::Family::kMultisine: {
        const std::vector<double> periods = Periods(in, layout.duration);
        std::vector<double> amplitude(periods.size()), phase(periods.size());
        for (size_t k = 0; k < periods.size(); ++k) {
          amplitude[k] = v[2 * k] * 0.5 * (in.upper - in.lower);
          phase[k] = 2.0 * kDesignPi * v[2 * k + 1];
        }
        const double value = in.value;
        parts.push_back([periods, amplitude, phase, value](double t, const double*, int*) {
          double c = value;
          for (size_t k = 0; k < periods.size(); ++k) {
            c += amplitude[k] * std::sin(2.0 * kDesignPi * t / periods[k] + phase[k]);
          }
          return c;
        });
        break;
      }
      case DesignInput::Family::kZigzag: {
        zigzag->rudder = v[0] * std::max(std::abs(in.lower), std::abs(in.upper));
        zigzag->heading = in.headings.first + v[1] * (in.headings.second - in.headings.first);
        const int psi = layout.heading;
        parts.push_back([zigzag, psi](double, const double* y, int* reversals) {
          return zigzag->Next(y[psi], reversals);
        });
        break;
      }
      case DesignInput::Family::kFixed: {
        const double value = in.value;
        parts.push_back([value](double, const double*, int*) { return value; });
        break;
      }
    }
  }
  std::vector<int> index = layout.input;
  return Holding(nominal, [parts, index](double t, const double* y, double* c, int* reversals) {
    for (size_t d = 0; d < parts.size(); ++d) c[index[d]] = parts[d](t, y, reversals);
  });
}

Manoeuvre Zigzag(const DesignOptions& options, const DesignLayout& layout, double rudder,
                 double heading) {
  auto state = std::make_shared<ZigzagState>();
  state->rudder = rudder;
  state->heading = heading;
  const int delta = layout.rudder, psi = layout.heading;
  return Holding(Nominal(options, layout),
                 [state, delta, psi](double, const double* y, double* c, int* reversals) {
                   c[delta] = state->Next(y[psi], reversals);
                 });
}

std::vector<std::pair<std::string, Manoeuvre>> Alternatives(const DesignOptions& options,
                                                            const DesignLayout& layout) {
  std::vector<std::pair<std::string, Manoeuvre>> out;
  const std::vector<double> nominal = Nominal(options, layout);
  const double duration = layout.duration;
  // The rudder's own limit (the zigzags and spiral are clipped to it by the actuator).
  bool rudder_planned = false;
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    rudder_planned = rudder_planned || (layout.input[d] == layout.rudder &&
                                        options.inputs[d].family != DesignInput::Family::kFixed);
  }
  if (rudder_planned && layout.heading >= 0) {
    out.emplace_back("zigzag_10_10",
                     Zigzag(options, layout, 10 * kDesignDegree, 10 * kDesignDegree));
    out.emplace_back("zigzag_20_20",
                     Zigzag(options, layout, 20 * kDesignDegree, 20 * kDesignDegree));
    const int delta = layout.rudder;
    out.emplace_back("spiral",
                     Holding(nominal, [duration, delta](double t, const double*, double* c, int*) {
                       static constexpr double kSteps[] = {25, 15, 5, -5, -15, -25};
                       const int j = std::min(5, static_cast<int>(6.0 * t / duration));
                       c[delta] = kSteps[j] * kDesignDegree;
                     }));
  }
  // Schroeder-phased multi-sine (phi_k = -pi k (k - 1) / K) of harmonics 1..K of the
  // duration, equal amplitudes, peaking at the nearer limit; the inputs shifted by a quarter
  // of the record from one another so that they are not alike.
  std::vector<int> excited;
  std::vector<DesignInput> limits;
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    if (options.inputs[d].family == DesignInput::Family::kFixed) continue;
    excited.push_back(layout.input[d]);
    limits.push_back(options.inputs[d]);
  }
  constexpr int kHarmonics = 8;
  auto schroeder = [duration](double t) {
    double sum = 0.0;
    for (int k = 1; k <= kHarmonics; ++k) {
      sum += std::cos(2.0 * kDesignPi * k * t / duration - kDesignPi * k * (k - 1) / kHarmonics);
    }
    return sum;
  };
  double peak = 0.0;
  for (int j = 0; j < 4000; ++j) peak = std::max(peak, std::abs(schroeder(duration * j / 4000.0)));
  out.emplace_back("multisine", Holding(nominal, [=](double t, const double*, double* c, int*) {
                     for (size_t e = 0; e < excited.size(); ++e) {
                       const DesignInput& in = limits[e];
                       // Peaks at the nearer limit around the input's nominal value.
                       const double half = std::min(in.upper - in.value, in.value - in.lower) > 0.0
                                               ? std::min(in.upper - in.value, in.value - in.lower)
                                               : 0.5 * (in.upper - in.lower);
                       const double shift = 0.25 * duration * static_cast<double>(e);
                       c[excited[e]] = in.value + half * schroeder(t + shift) / peak;
                     }
                   }));
  // Random binary sequence: each input at its lower or upper limit, switched with
  // probability 1/2 every twentieth of the record (seed 1: the same sequence every time).
  std::mt19937 random(1);
  std::vector<std::vector<double>> levels(excited.size());
  for (size_t e = 0; e < excited.size(); ++e) {
    for (int j = 0; j < 20; ++j) {
      levels[e].push_back(random() % 2 == 0 ? limits[e].lower : limits[e].upper);
    }
  }
  out.emplace_back("prbs", Holding(nominal, [=](double t, const double*, double* c, int*) {
                     const int j = std::min(19, static_cast<int>(20.0 * t / duration));
                     for (size_t e = 0; e < excited.size(); ++e) c[excited[e]] = levels[e][j];
                   }));
  return out;
}

}  // namespace vesselid
