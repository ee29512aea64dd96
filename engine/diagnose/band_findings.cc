#include "engine/diagnose/band_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

double PredictionBandLimit(const RunResult& run) {
  double share = 0.0;
  for (auto s = run.stages.rbegin(); s != run.stages.rend(); ++s) {
    if (!s->rejected.empty() || s->summary.fits.empty()) continue;
    for (const ResidualAnalysis& a : s->residuals) {
      if (std::isfinite(a.input_noise_share)) share = std::max(share, a.input_noise_share);
    }
    break;
  }
  share = std::clamp(share, 0.0, 1.0);
  return (1.0 - share) * kBandWhiteLimit + share * kBandInputNoiseLimit;
}

void AddPredictionBandFindings(const RunResult& run, std::vector<Finding>* findings) {
  const double limit = PredictionBandLimit(run);
  for (const ExperimentFit& fit : run.final_validation) {
    const PredictionBand& band = fit.band;
    if (!band.done || !(band.ratio > limit)) continue;
    // The output whose own error is largest against the training fit's.
    size_t worst = 0;
    for (size_t o = 1; o < band.outputs.size(); ++o) {
      if (band.output_ratio[o] > band.output_ratio[worst]) worst = o;
    }
    char text[640];
    std::snprintf(text, sizeof(text),
                  "held-out run '%s', flown from its measured start, is predicted worse than the "
                  "fit and its uncertainty explain: its mean square error is %.3g times the "
                  "training fit's (%s: %.3g), and %.3g times after the best adjustment of the "
                  "estimates and of its start within their standard errors (limit %.3g): the "
                  "model's structure does not carry over to this run",
                  fit.experiment.c_str(), band.raw_ratio,
                  band.outputs.empty() ? "" : band.outputs[worst].c_str(),
                  band.outputs.empty() ? band.raw_ratio : band.output_ratio[worst], band.ratio,
                  limit);
    Finding f = MakeFinding(FindingKind::kHeldOutBeyondBand, text);
    f.stage = "final";
    f.experiment = fit.experiment;
    if (!band.outputs.empty()) f.output = band.outputs[worst];
    f.value = band.ratio;
    f.threshold = limit;
    findings->push_back(std::move(f));
  }
}

}  // namespace vesselid
