#include "engine/run/disturbance_notes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace vesselid {
namespace {

// A noise parameter within this fraction of a bound is at it.
constexpr double kNoiseBoundTolerance = 1e-3;

// A value in the unit the user reads: an angle output's in degrees.
std::string Amount(double value, double se, bool angle, const std::string& unit) {
  const double factor = angle ? 180.0 / M_PI : 1.0;
  std::string shown = unit;
  if (angle && unit.rfind("rad", 0) == 0) shown = "deg" + unit.substr(3);
  char text[96];
  if (std::isfinite(se)) {
    std::snprintf(text, sizeof(text), "%.3g %s (SE %.2g)", value * factor, shown.c_str(),
                  se * factor);
  } else {
    std::snprintf(text, sizeof(text), "%.3g %s", value * factor, shown.c_str());
  }
  return text;
}

}  // namespace

std::string DescribeDisturbance(const OutputErrorProblem& problem, const Uncertainty& uncertainty) {
  const ModelInfo& info = problem.model().info();
  const DisturbanceLayout& layout = problem.disturbance();
  std::vector<double> value(layout.size()), se(layout.size(), NAN);
  std::vector<std::string> bounded;  // the noise parameters held at a bound
  for (size_t i = 0; i < problem.variables().size(); ++i) {
    const Variable& v = problem.variables()[i];
    if (v.kind != Variable::Kind::kNoise) continue;
    value[v.index] = v.value();
    se[v.index] = uncertainty.StdError(static_cast<int>(i));
    // The noise parameters are positive with bounds decades apart: a relative test.
    if (v.free && (v.value() <= v.lower * (1.0 + kNoiseBoundTolerance) ||
                   v.value() >= v.upper * (1.0 - kNoiseBoundTolerance))) {
      bounded.push_back(v.name);
    }
  }
  // An AR(1) part slower than the longest record is a drift, not a sensor's noise: the record
  // cannot tell it from a bias or from slow structure the ship model lacks.
  double longest = 0.0;
  for (const Experiment& e : problem.experiments()) {
    if (e.num_nodes() > 1) longest = std::max(longest, e.node_time.back() - e.node_time.front());
  }
  auto angle_of = [&](int j) {
    return j < static_cast<int>(info.angle_outputs.size()) && info.angle_outputs[j];
  };
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  for (size_t j = 0; j < layout.outputs.size(); ++j) {
    const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
    const bool angle = angle_of(static_cast<int>(j));
    const std::string unit = info.OutputUnit(static_cast<int>(j));
    std::string part;
    auto piece = [&](const std::string& s) { part += (part.empty() ? "" : ", ") + s; };
    if (o.ar1_state >= 0) {
      const bool drift = longest > 0.0 && value[o.ar1_tau] > longest;
      piece(std::string(drift ? "a drift slower than the record (AR(1) tau "
                              : "sensor noise AR(1) tau ") +
            Amount(value[o.ar1_tau], se[o.ar1_tau], false, "s") + (drift ? ")" : "") + " SD " +
            Amount(value[o.ar1_sigma], se[o.ar1_sigma], angle, unit));
    }
    if (o.wave_state >= 0) {
      piece("wave-frequency part, peak " +
            Amount(value[o.wave_omega], se[o.wave_omega], false, "rad/s") + " damping " +
            Amount(value[o.wave_zeta], se[o.wave_zeta], false, "") + " SD " +
            Amount(value[o.wave_sigma], se[o.wave_sigma], angle, unit));
    }
    if (o.bias_state >= 0) {
      // A random walk's spread over a minute says more than its spectral density: its SD
      // grows as sqrt(q t), so per square-root minute.
      const double minute = std::sqrt(value[o.bias_q] * 60.0);
      const double minute_se = std::isfinite(se[o.bias_q]) && value[o.bias_q] > 0.0
                                   ? 0.5 * minute * se[o.bias_q] / value[o.bias_q]
                                   : NAN;
      piece("drifting bias (random walk), " + Amount(minute, minute_se, angle, unit) +
            " per sqrt(minute)");
    }
    if (o.white >= 0) piece("white " + Amount(value[o.white], se[o.white], angle, unit));
    if (!part.empty()) add(info.outputs[j] + ": " + part);
  }
  for (size_t s = 0; s < layout.process.size(); ++s) {
    const int q = layout.process[s];
    if (q < 0) continue;
    const std::string unit = info.StateUnit(static_cast<int>(s));
    const std::string squared = unit.empty() ? ""
                                : unit.find_first_of("/^*") == std::string::npos
                                    ? unit + "^2/s"
                                    : "(" + unit + ")^2/s";
    add("process noise on " + info.states[s] + "'s equation, spectral density " +
        Amount(value[q], se[q], false, squared));
  }
  if (!bounded.empty()) {
    std::string names;
    for (const std::string& n : bounded) names += (names.empty() ? "" : ", ") + n;
    add("at a bound (" + names + "): that part is not what the data show (at a lower bound, " +
        "absent)");
  }
  return text.empty() ? "none" : text;
}

void DisturbanceNotes(const std::string& stage, const OutputErrorProblem& problem,
                      const Uncertainty& uncertainty,
                      const std::vector<ResidualAnalysis>& innovations,
                      std::vector<std::string>* notes, std::vector<Finding>* findings) {
  if (!problem.filter_error()) return;
  const double nll = problem.NegativeLogLikelihood();
  char text[160];
  std::snprintf(text, sizeof(text),
                "filter-error method: %s; -log likelihood %.6g over %d samples",
                problem.disturbance().Describe().c_str(), nll, problem.num_samples());
  notes->push_back(text);
  std::map<std::string, std::pair<int, int>> white;  // output: white, tested
  for (const ResidualAnalysis& a : innovations) {
    if (!a.tested()) continue;
    ++white[a.output].second;
    if (!a.coloured()) ++white[a.output].first;
  }
  std::string whiteness;
  for (const auto& [output, counts] : white) {
    char part[96];
    std::snprintf(part, sizeof(part), "%s%s white in %d of %d", whiteness.empty() ? "" : ", ",
                  output.c_str(), counts.first, counts.second);
    whiteness += part;
  }
  Finding f = MakeFinding(FindingKind::kDisturbanceModel,
                          "the disturbance identified with the ship: " +
                              DescribeDisturbance(problem, uncertainty) +
                              (whiteness.empty() ? std::string()
                                                 : "; the filter's innovations: " + whiteness));
  f.stage = stage;
  findings->push_back(std::move(f));
}

}  // namespace vesselid
