#include "engine/run/input_noise_notes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

void InputNoiseNotes(const OutputErrorProblem& problem, std::vector<std::string>* notes_out,
                     std::vector<Finding>* findings) {
  std::vector<std::string>& notes = *notes_out;
  const ModelInfo& info = problem.model().info();
  std::string noisy;  // "delta 0.1 deg" per noisy input, for the bootstrap suggestion
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& experiment = problem.experiments()[e];
    const std::vector<double> c = problem.InputCorrectionsOf(static_cast<int>(e));
    for (const LatentInput& latent : experiment.latent_inputs) {
      const double unit = latent.degrees ? 180.0 / M_PI : 1.0;
      const char* label = latent.degrees ? " deg" : "";
      char text[512];
      std::snprintf(text, sizeof(text),
                    "input noise: experiment '%s' input '%s' (column '%s'): sigma %.3g%s (%s; "
                    "second differences say %.3g%s), latent spline knots every %.3g s",
                    experiment.name.c_str(), info.inputs[latent.input].c_str(),
                    latent.column.c_str(), latent.sigma * unit, label,
                    latent.sigma_estimated ? "estimated" : "given", latent.noise_level * unit,
                    label, latent.knot_spacing);
      std::string note = text;
      for (const InputCorrectionGrid& g : experiment.input_corrections) {
        if (g.input != latent.input || g.count == 0) continue;
        double sum2 = 0.0, low = c[g.offset], high = c[g.offset];
        for (int j = 0; j < g.count; ++j) {
          const double v = c[g.offset + j];
          sum2 += v * v;
          low = std::min(low, v);
          high = std::max(high, v);
        }
        std::snprintf(text, sizeof(text),
                      "; %d low-frequency corrections every %.4g s: RMS %.3g%s (prior SD "
                      "%.3g%s), range [%.3g, %.3g]%s",
                      g.count, g.spacing, std::sqrt(sum2 / g.count) * unit, label, g.sigma * unit,
                      label, low * unit, high * unit, label);
        note += text;
      }
      notes.push_back(note);
      const std::string name = info.inputs[latent.input];
      if (noisy.find(name + ":") == std::string::npos) {
        std::snprintf(text, sizeof(text), "%s%s: %.3g", noisy.empty() ? "" : ", ", name.c_str(),
                      latent.sigma);
        noisy += text;
      }
    }
  }
  if (!noisy.empty()) {
    findings->push_back(MakeFinding(
        FindingKind::kNarrowIntervals,
                    "the standard errors hold the latent input splines as exact and miss the "
                    "input noise they pass, so they may be too narrow (1.5-2.3x in the cargo "
                    "multi-sine Monte Carlo); for intervals run the parametric bootstrap "
                    "`study: {monte_carlo: {truth: estimate, noise: {" + noisy + "}}}` (SD in "
                    "model units), which fits the splines again in every run"));
  }
}

}  // namespace vesselid
