#include "engine/diagnose/band_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace vesselid {
namespace {

std::string FormatShift(double standard_errors) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.1f of its standard errors", standard_errors);
  return text;
}

}  // namespace

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
    if (band.done && band.consistency_p < kConsistencyLimitP) {
      char text[640];
      std::snprintf(text, sizeof(text),
                    "held-out run '%s', flown from its measured start, asks for other values "
                    "than the training runs gave: chi-square %.3g on %d degrees of freedom "
                    "(p = %.2g, limit %.2g)%s%s%s: the values depend on the run, which the "
                    "model's structure does not represent",
                    fit.experiment.c_str(), band.consistency, band.consistency_dof,
                    band.consistency_p, kConsistencyLimitP,
                    band.worst_parameter.empty() ? "" : "; refitted on it, ",
                    band.worst_parameter.c_str(),
                    band.worst_parameter.empty()
                        ? ""
                        : (" would move by " + FormatShift(band.worst_shift)).c_str());
      Finding f = MakeFinding(FindingKind::kHeldOutInconsistent, text);
      f.stage = "final";
      f.experiment = fit.experiment;
      if (!band.worst_parameter.empty()) f.parameter = band.worst_parameter;
      f.value = band.consistency_p;
      f.threshold = kConsistencyLimitP;
      findings->push_back(std::move(f));
    }
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
