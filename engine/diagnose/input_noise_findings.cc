#include "engine/diagnose/input_noise_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/data/noise_level.h"

namespace vesselid {
namespace {

constexpr double kRatio = 1e-3;          // noise SD / signal SD below which noise is ignored
constexpr double kWhiteCorrelation = -0.3;  // lag-1 correlation of first differences
constexpr double kRepeatShare = 0.2;        // share of exact repeats that marks a held input
constexpr int kBlock = 20;               // samples per block mean
constexpr double kColouredRatio = 2.0;

}  // namespace

double WhiteInputNoise(const std::vector<double>& values) {
  const size_t n = values.size();
  if (n < 50) return 0.0;
  NoiseLevel level;
  double mean = 0.0;
  int repeats = 0;
  for (size_t k = 0; k < n; ++k) {
    level.Add(values[k]);
    mean += values[k];
    if (k > 0 && values[k] == values[k - 1]) ++repeats;
  }
  if (repeats > kRepeatShare * (n - 1)) return 0.0;
  mean /= n;
  double variance = 0.0;
  for (double v : values) variance += (v - mean) * (v - mean);
  const double sd = std::sqrt(variance / n), sigma = level.Sigma();
  if (!(sigma >= kRatio * sd) || !(sigma > 0.0)) return 0.0;
  double s01 = 0.0, s00 = 0.0, s11 = 0.0;
  for (size_t k = 2; k < n; ++k) {
    const double d1 = values[k] - values[k - 1], d0 = values[k - 1] - values[k - 2];
    s01 += d0 * d1;
    s00 += d0 * d0;
    s11 += d1 * d1;
  }
  const double correlation = s01 / std::sqrt(s00 * s11);
  return correlation < kWhiteCorrelation ? sigma : 0.0;
}

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
    for (const StageResult& stage : run.stages) {
      for (const ExperimentFit& fit : stage.summary.fits) {
        if (fit.experiment != spec.name && fit.experiment.rfind(spec.name + "@", 0) != 0 &&
            fit.experiment.rfind(spec.name + "#", 0) != 0) {
          continue;
        }
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
      if (spec.input_noise.count(input) > 0 || info.InputIndex(input) < 0) continue;
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values)) continue;
      const double sigma = WhiteInputNoise(values);
      if (!(sigma > 0.0)) continue;
      const bool degrees = std::find(spec.degree_columns.begin(), spec.degree_columns.end(),
                                     column) != spec.degree_columns.end();
      const std::string unit = degrees ? "deg" : info.InputUnit(info.InputIndex(input));
      char text[512];
      std::snprintf(text, sizeof(text),
                    "input %s (column '%s'): white noise of SD %.3g %s on the "
                    "measured input, and the fit's residuals are coloured: the simulation "
                    "integrates the noise, which biases fast parameters and makes the standard "
                    "errors too small; consider input_noise: {%s: auto}",
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
