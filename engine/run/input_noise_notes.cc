#include "engine/run/input_noise_notes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

std::vector<std::string> InputNoiseNotes(const OutputErrorProblem& problem) {
  std::vector<std::string> notes;
  const ModelInfo& info = problem.model().info();
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
    }
  }
  return notes;
}

}  // namespace vesselid
