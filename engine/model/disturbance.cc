#include "engine/model/disturbance.h"

#include <algorithm>
#include <cmath>

namespace vesselid {

const char* DisturbanceMethodToString(DisturbanceSpec::Method method) {
  switch (method) {
    case DisturbanceSpec::Method::kOutputError:
      return "output_error";
    case DisturbanceSpec::Method::kFilterError:
      return "filter_error";
    case DisturbanceSpec::Method::kAuto:
      return "auto";
  }
  return "output_error";
}

bool StringToDisturbanceMethod(const std::string& text, DisturbanceSpec::Method* method) {
  for (DisturbanceSpec::Method m :
       {DisturbanceSpec::Method::kOutputError, DisturbanceSpec::Method::kFilterError,
        DisturbanceSpec::Method::kAuto}) {
    if (text == DisturbanceMethodToString(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

std::string DisturbanceLayout::Names() const {
  std::string text;
  for (const NoiseParameter& p : parameters) text += (text.empty() ? "" : ", ") + p.name;
  return text;
}

std::string DisturbanceLayout::Describe() const {
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : " + ") + part; };
  std::vector<std::string> white, ar1, wave, bias, process;
  for (const NoiseParameter& p : parameters) {
    const std::string target = p.name.substr(p.name.rfind('.') + 1);
    switch (p.kind) {
      case NoiseParameter::Kind::kWhiteSigma:
        white.push_back(target);
        break;
      case NoiseParameter::Kind::kAr1Tau:
        ar1.push_back(target);
        break;
      case NoiseParameter::Kind::kWaveOmega:
        wave.push_back(target);
        break;
      case NoiseParameter::Kind::kBiasQ:
        bias.push_back(target);
        break;
      case NoiseParameter::Kind::kProcessQ:
        process.push_back(target);
        break;
      default:
        break;
    }
  }
  auto join = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  };
  if (!white.empty()) add("white(" + join(white) + ")");
  if (!ar1.empty()) add("ar1(" + join(ar1) + ")");
  if (!wave.empty()) add("wave(" + join(wave) + ")");
  if (!bias.empty()) add("bias(" + join(bias) + ")");
  if (!process.empty()) add("process(" + join(process) + ")");
  return text.empty() ? "none" : text;
}

namespace {

// "rad" -> "rad^2", "rad/s^2" -> "(rad/s^2)^2".
std::string Squared(const std::string& unit) {
  if (unit.empty()) return "";
  return unit.find_first_of("/^*") == std::string::npos ? unit + "^2" : "(" + unit + ")^2";
}

}  // namespace

bool BuildDisturbanceLayout(const DisturbanceSpec& spec, const ModelInfo& info,
                            const DisturbanceScales& scales, DisturbanceLayout* layout,
                            std::string* error) {
  *layout = DisturbanceLayout();
  const int ny = static_cast<int>(info.outputs.size());
  const int nx = static_cast<int>(info.states.size());
  layout->outputs.assign(ny, {});
  layout->process.assign(nx, -1);
  layout->steady_gain = spec.steady_gain;
  auto level = [&](int j) {
    const double l = j < static_cast<int>(scales.noise_level.size()) ? scales.noise_level[j] : NAN;
    return l > 0.0 && std::isfinite(l) ? l : 1e-3;
  };
  auto add = [&](NoiseParameter p) {
    layout->parameters.push_back(p);
    return layout->size() - 1;
  };
  auto positive = [](NoiseParameter p, double start, double below, double above) {
    p.start = start;
    p.lower = start * below;
    p.upper = start * above;
    return p;
  };
  std::vector<bool> compared(ny, false), listed(ny, false);
  for (int j : scales.compared) compared[j] = true;
  auto output_index = [&](const std::string& name, const std::string& key) {
    const int j = info.OutputIndex(name);
    if (j < 0) {
      *error = "disturbance " + key + ": unknown output '" + name + "' (model " + info.name +
               " has " + JoinNames(info.outputs) + ")";
    } else if (!compared[j]) {
      *error = "disturbance " + key + ": output '" + name + "' is not compared by the stage";
      return -1;
    }
    return j;
  };
  const double dt = scales.sample_interval > 0.0 ? scales.sample_interval : 1.0;

  for (const DisturbanceSpec::Measurement& m : spec.measurement) {
    const int j = output_index(m.output, "measurement");
    if (j < 0) return false;
    if (listed[j]) {
      *error = "disturbance measurement: output '" + m.output + "' listed twice";
      return false;
    }
    listed[j] = true;
    const std::string unit = info.OutputUnit(j);
    DisturbanceLayout::OutputNoise& o = layout->outputs[j];
    const double sigma = std::isfinite(m.sigma) && m.sigma > 0.0 ? m.sigma : level(j);
    if (m.type == DisturbanceSpec::Measurement::Type::kWhite || m.white_too) {
      NoiseParameter p;
      p.kind = NoiseParameter::Kind::kWhiteSigma;
      p.target = j;
      p.name = "sigma.white." + info.outputs[j];
      p.unit = unit;
      o.white = add(positive(p, m.type == DisturbanceSpec::Measurement::Type::kWhite ? sigma
                                                                                      : 0.3 * sigma,
                             1e-4, 1e4));
    }
    if (m.type == DisturbanceSpec::Measurement::Type::kAr1) {
      NoiseParameter s;
      s.kind = NoiseParameter::Kind::kAr1Sigma;
      s.target = j;
      s.name = "sigma.ar1." + info.outputs[j];
      s.unit = unit;
      o.ar1_sigma = add(positive(s, sigma, 1e-4, 1e4));
      NoiseParameter t;
      t.kind = NoiseParameter::Kind::kAr1Tau;
      t.target = j;
      t.name = "tau.ar1." + info.outputs[j];
      t.unit = "s";
      const double tau = std::isfinite(m.tau) && m.tau > 0.0 ? m.tau : std::max(1.0, 2.0 * dt);
      t.start = tau;
      t.lower = 0.05 * dt;
      t.upper = std::max(1e4, 10.0 * tau);
      o.ar1_tau = add(t);
      o.ar1_state = layout->num_states++;
    }
  }
  for (int j : scales.compared) {
    if (listed[j]) continue;
    NoiseParameter p;
    p.kind = NoiseParameter::Kind::kWhiteSigma;
    p.target = j;
    p.name = "sigma.white." + info.outputs[j];
    p.unit = info.OutputUnit(j);
    layout->outputs[j].white = add(positive(p, level(j), 1e-4, 1e4));
  }
  for (const DisturbanceSpec::Wave& w : spec.wave) {
    const int j = output_index(w.output, "wave");
    if (j < 0) return false;
    DisturbanceLayout::OutputNoise& o = layout->outputs[j];
    if (o.wave_state >= 0) {
      *error = "disturbance wave: output '" + w.output + "' listed twice";
      return false;
    }
    if (!(w.omega > 0.0) || !(w.zeta > 0.0 && w.zeta < 1.0)) {
      *error = "disturbance wave." + w.output + ": omega must be > 0 and zeta in (0, 1)";
      return false;
    }
    NoiseParameter omega;
    omega.kind = NoiseParameter::Kind::kWaveOmega;
    omega.target = j;
    omega.name = "omega.wave." + info.outputs[j];
    omega.unit = "rad/s";
    omega.start = w.omega;
    omega.lower = 0.02;
    omega.upper = std::max(3.0 * w.omega, 0.9 * M_PI / dt);  // below the sampling's Nyquist
    o.wave_omega = add(omega);
    NoiseParameter zeta;
    zeta.kind = NoiseParameter::Kind::kWaveZeta;
    zeta.target = j;
    zeta.name = "zeta.wave." + info.outputs[j];
    zeta.start = w.zeta;
    zeta.lower = 0.005;
    zeta.upper = 0.95;
    o.wave_zeta = add(zeta);
    NoiseParameter sigma;
    sigma.kind = NoiseParameter::Kind::kWaveSigma;
    sigma.target = j;
    sigma.name = "sigma.wave." + info.outputs[j];
    sigma.unit = info.OutputUnit(j);
    o.wave_sigma = add(positive(
        sigma, std::isfinite(w.sigma) && w.sigma > 0.0 ? w.sigma : 3.0 * level(j), 1e-4, 1e4));
    o.wave_state = layout->num_states;
    layout->num_states += 2;
  }
  for (const DisturbanceSpec::Bias& b : spec.bias) {
    const int j = output_index(b.output, "bias");
    if (j < 0) return false;
    DisturbanceLayout::OutputNoise& o = layout->outputs[j];
    if (o.bias_state >= 0) {
      *error = "disturbance bias: output '" + b.output + "' listed twice";
      return false;
    }
    NoiseParameter q;
    q.kind = NoiseParameter::Kind::kBiasQ;
    q.target = j;
    q.name = "q.bias." + info.outputs[j];
    q.unit = Squared(info.OutputUnit(j)) + "/s";
    const double start =
        std::isfinite(b.q) && b.q > 0.0 ? b.q : level(j) * level(j) / 100.0;  // a level per 100 s
    o.bias_q = add(positive(q, start, 1e-8, 1e6));
    o.bias_initial_sd =
        std::isfinite(b.initial_sd) && b.initial_sd > 0.0 ? b.initial_sd : 10.0 * level(j);
    o.bias_state = layout->num_states++;
  }
  for (const DisturbanceSpec::Process& w : spec.process) {
    const int i = info.StateIndex(w.state);
    if (i < 0) {
      *error = "disturbance process: unknown state '" + w.state + "' (model " + info.name +
               " has " + JoinNames(info.states) + ")";
      return false;
    }
    if (layout->process[i] >= 0) {
      *error = "disturbance process: state '" + w.state + "' listed twice";
      return false;
    }
    NoiseParameter q;
    q.kind = NoiseParameter::Kind::kProcessQ;
    q.target = i;
    q.name = "q.process." + info.states[i];
    q.unit = Squared(info.StateUnit(i)) + "/s";
    const double magnitude =
        i < static_cast<int>(scales.state_magnitude.size()) && scales.state_magnitude[i] > 0.0
            ? scales.state_magnitude[i]
            : 1.0;
    // A start whose random walk moves the state by 1 % of its range in one second.
    const double start = std::isfinite(w.q) && w.q > 0.0 ? w.q : std::pow(0.01 * magnitude, 2);
    layout->process[i] = add(positive(q, start, 1e-10, 1e6));
  }
  if (layout->num_states > kMaxDisturbanceStates) {
    *error = "disturbance: " + std::to_string(layout->num_states) +
             " disturbance states, at most " + std::to_string(kMaxDisturbanceStates);
    return false;
  }
  for (int j = 0; j < ny; ++j) {
    // A variance floor far below any sensor's (1e-6 of the noise level): keeps the innovation
    // variance positive where the parts above vanish.
    layout->outputs[j].floor = std::pow(1e-6 * level(j), 2);
  }
  return true;
}

}  // namespace vesselid
