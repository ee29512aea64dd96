#include "engine/diagnose/input_noise_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "engine/data/white_noise.h"

namespace vesselid {
namespace {

constexpr int kBlock = 20;               // samples per block mean
constexpr double kColouredRatio = 2.0;

}  // namespace

bool ResidualsColoured(const std::vector<double>& r) {
  const size_t blocks = r.size() / kBlock;
  if (blocks < 20) return false;
  double sum = 0.0, sum2 = 0.0, means2 = 0.0, means = 0.0;
  for (size_t b = 0; b < blocks; ++b) {
    double m = 0.0;
    for (int i = 0; i < kBlock; ++i) m += r[b * kBlock + i];
    m /= kBlock;
    means += m;
    means2 += m * m;
  }
  const size_t n = blocks * kBlock;
  for (size_t i = 0; i < n; ++i) {
    sum += r[i];
    sum2 += r[i] * r[i];
  }
  const double variance = sum2 / n - (sum / n) * (sum / n);
  const double mean_variance = means2 / blocks - (means / blocks) * (means / blocks);
  return variance > 0.0 && mean_variance * kBlock > kColouredRatio * variance;
}

void AddInputNoiseFindings(const RunConfig& config, const RunResult& run, TrajectoryCache* cache,
                           std::vector<Finding>* findings) {
  const ModelInfo& info = config.model->info();
  for (const ExperimentSpec& spec : config.experiments) {
    // Coloured residuals in any stage fit of this experiment (or of its segments).
    bool coloured = false;
    // Inputs of this experiment whose noise the last stage fitting it put in its standard
    // errors (input_noise_uncertainty.h): no finding for them.
    std::set<std::string> included;
    const auto of_spec = [&spec](const std::string& name) {
      return name == spec.name || name.rfind(spec.name + "@", 0) == 0 ||
             name.rfind(spec.name + "#", 0) == 0;
    };
    for (const StageResult& stage : run.stages) {
      bool fitted = false;
      for (const ExperimentFit& fit : stage.summary.fits) fitted |= of_spec(fit.experiment);
      // A filter-error stage's free run is coloured by the identified gusts whatever the
      // inputs' noise, and its innovations are judged elsewhere (disturbance_notes.h); input
      // corrections are not available to it either (a noisy input is process noise there).
      if (!fitted || stage.disturbance.filter_error) continue;
      included.clear();
      for (const std::string& key : stage.summary.uncertainty.input_noise_inputs) {
        const size_t colon = key.rfind(':');
        if (colon != std::string::npos && of_spec(key.substr(0, colon))) {
          included.insert(key.substr(colon + 1));
        }
      }
      for (const ExperimentFit& fit : stage.summary.fits) {
        if (!of_spec(fit.experiment)) continue;
        const Trajectory& trace = fit.trace;
        for (size_t c = 0; c + 1 < trace.names.size(); ++c) {
          const std::string& name = trace.names[c];
          if (name.size() < 9 || name.compare(name.size() - 9, 9, "_measured") != 0) continue;
          std::vector<double> r;
          for (size_t k = 0; k < trace.t.size(); ++k) {
            const double d = trace.columns[c + 1][k] - trace.columns[c][k];
            if (std::isfinite(d)) r.push_back(d);
          }
          coloured |= ResidualsColoured(r);
        }
      }
    }
    if (!coloured) continue;
    for (const auto& [input, column] : spec.inputs) {
      if (spec.input_noise.count(input) > 0 || info.InputIndex(input) < 0 ||
          included.count(input) > 0) {
        continue;
      }
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values)) continue;
      const double sigma = WhiteInputNoise(values);
      if (!(sigma > 0.0)) continue;
      const bool degrees = spec.IsDegreeColumn(column);
      const std::string unit = degrees ? "deg" : info.InputUnit(info.InputIndex(input));
      char text[512];
      std::snprintf(text, sizeof(text),
                    "input %s (column '%s'): white noise of SD %.3g %s on the "
                    "measured input, and the fit's residuals are coloured: the simulation "
                    "integrates the noise, which biases fast parameters and makes the standard "
                    "errors too small; keep the stage's default uncertainty: {input_noise: auto} "
                    "(refits with the noise added again) or declare the experiment's "
                    "input_noise: {%s: auto} (a latent input)",
                    input.c_str(), column.c_str(),
                    degrees ? sigma * 180.0 / M_PI : sigma, unit.c_str(),
                    input.c_str());
      Finding f = MakeFinding(FindingKind::kInputNoise, text);
      f.experiment = spec.name;
      f.input = input;
      f.value = degrees ? sigma * 180.0 / M_PI : sigma;
      findings->push_back(std::move(f));
    }
  }
}

}  // namespace vesselid
