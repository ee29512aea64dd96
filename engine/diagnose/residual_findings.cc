#include "engine/diagnose/residual_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace vesselid {
namespace {

constexpr size_t kNamed = 6;  // experiments named in a warning at most

// Residual structure that noise does not give: a lag-1 autocorrelation above kStrongLag1 where
// the fit's RMSE, without the part noise on a measured input can make (its 99 % quantile over
// the input noise refits, input_noise_uncertainty.h), is above kStrongNoiseRatio x the
// record's own noise level. On the independent corpus (tests/corpus), correct structures
// fitted to noisy records reach an RMSE of 1.03 x the noise with a lag-1 of 0.06 where the
// rudder is clean; the rudder's noise, integrated by psi' = r, takes them to lag-1 0.85 and
// 2.6 x, which its share brings back to 1.00-1.10 x. Wrong structures, held parameters and
// unmodelled disturbances reach lag-1 0.3-0.95 at 1.2-2.1 x. The lag-1 floor leaves room for
// a real sensor's mildly coloured noise, which the second-difference noise level understates.
constexpr double kStrongLag1 = 0.3;
constexpr double kStrongNoiseRatio = 1.05;

std::string PValue(double p) {
  if (!(p >= 1e-16)) return "p < 1e-16";
  char text[32];
  std::snprintf(text, sizeof(text), "p %.2g", p);
  return text;
}

// r_1 to two decimals, without the sign of a value that rounds to zero.
double Lag1(double r) { return std::abs(r) < 0.005 ? 0.0 : r; }

// Worst first: largest |lag-1| correlation.
std::vector<const ResidualAnalysis*> Worst(std::vector<const ResidualAnalysis*> list) {
  std::stable_sort(list.begin(), list.end(),
                   [](const ResidualAnalysis* a, const ResidualAnalysis* b) {
                     return std::abs(a->lag1) > std::abs(b->lag1);
                   });
  return list;
}

// "run3 (lag-1 0.93), run1 (lag-1 0.40)", or with `inputs` "run3 (delta)": the correlated
// inputs; at most kNamed.
std::string Experiments(const std::vector<const ResidualAnalysis*>& list, bool inputs) {
  std::string text;
  for (size_t i = 0; i < list.size() && i < kNamed; ++i) {
    std::string detail;
    if (inputs) {
      for (const ResidualCrossCorrelation& c : list[i]->cross_correlation) {
        if (c.correlated) detail += (detail.empty() ? "" : ", ") + c.input;
      }
    } else {
      char lag1[32];
      std::snprintf(lag1, sizeof(lag1), "lag-1 %.2f", Lag1(list[i]->lag1));
      detail = lag1;
    }
    text += (i > 0 ? ", " : "") + list[i]->experiment + " (" + detail + ")";
  }
  if (list.size() > kNamed) text += ", ...";
  return text;
}

}  // namespace

std::string DescribeResiduals(const ResidualAnalysis& a) {
  char text[160];
  if (!a.tested()) {
    std::snprintf(text, sizeof(text), "not tested (%d samples)", a.samples);
    return text;
  }
  const std::string p = PValue(a.ljung_box_p);
  if (a.white) {
    std::snprintf(text, sizeof(text), "white (lag-1 %.2f, %s)", Lag1(a.lag1), p.c_str());
  } else {
    std::snprintf(text, sizeof(text), "coloured (lag-1 %.2f, Ljung-Box %s)", Lag1(a.lag1),
                  p.c_str());
  }
  std::string out = text;
  std::string inputs;
  for (const ResidualCrossCorrelation& c : a.cross_correlation) {
    if (c.correlated) inputs += (inputs.empty() ? "" : ", ") + c.input;
  }
  if (!inputs.empty()) out += ", correlated with past " + inputs;
  if (a.noise_free) out += ", noise-free data (residuals are integration error): not warned";
  if (a.irregular()) {
    std::snprintf(text, sizeof(text), ", irregular sampling (intervals vary %.0f %%)",
                  100.0 * a.interval_spread);
    out += text;
  }
  return out;
}

std::string ColouredResidualWarning(const std::string& stage, const std::string& output,
                                    const std::vector<const ResidualAnalysis*>& coloured,
                                    int analysed, const Uncertainty& uncertainty) {
  char count[96];
  std::snprintf(count, sizeof(count),
                " in %zu of %d experiment(s) (Ljung-Box p < %g): ", coloured.size(), analysed,
                kWhitenessLevel);
  const std::string& reason = uncertainty.method_reason;
  std::string consequence;
  if (uncertainty.method == "hessian" && uncertainty.input_noise_runs > 0) {
    // The noise on a measured input, which colours the residuals, is in the standard errors
    // (input_noise_uncertainty.h).
    consequence = "; the standard errors reported add to the Hessian's the spread of refits "
                  "with the measured input's noise added again (" + reason + ")";
  } else if (uncertainty.method == "hessian" && reason.rfind("auto:", 0) == 0) {
    // `auto` kept the Hessian: the HAC beside it (uncertainty_method.h) found the intervals hold.
    consequence = "; the HAC standard errors, which allow for serially correlated residuals, "
                  "are close to the Hessian ones reported (" + reason + ")";
  } else if (uncertainty.method == "hessian") {
    consequence = "; the Hessian standard errors assume white residuals and are too narrow" +
                  (reason.empty() ? std::string() : " (" + reason + ")");
  } else {
    consequence = "; the standard errors reported are the " + uncertainty.method +
                  " ones, which allow for serially correlated residuals" +
                  (reason.empty() ? std::string() : " (" + reason + ")");
  }
  return "the residuals of " + output + " are coloured" + count +
         Experiments(Worst(coloured), false) + consequence;
}

std::string InputCorrelatedResidualWarning(const std::string& stage, const std::string& output,
                                           const std::vector<const ResidualAnalysis*>& correlated,
                                           int analysed) {
  char count[64];
  std::snprintf(count, sizeof(count), " in %zu of %d experiment(s): ", correlated.size(), analysed);
  return "the residuals of " + output + " are correlated with past inputs (beyond the 99 % band)" + count +
         Experiments(Worst(correlated), true) +
         ": dynamics the model leaves out, or noise on the measured input";
}

void AddResidualFindings(const StageResult& stage, std::vector<Finding>* findings) {
  // A failed fit has its own finding (FitFailed): its residuals are the signal.
  std::set<std::pair<std::string, std::string>> failed;
  for (const ExperimentFit& fit : stage.summary.fits) {
    for (const ChannelMetrics& m : fit.channels) {
      if (FitFailed(m)) failed.insert({m.experiment, m.output});
    }
  }
  std::map<std::pair<std::string, std::string>, const ChannelMetrics*> metrics;
  for (const ExperimentFit& fit : stage.summary.fits) {
    for (const ChannelMetrics& m : fit.channels) metrics[{m.experiment, m.output}] = &m;
  }
  std::vector<std::string> outputs;  // in order of appearance
  std::map<std::string, std::vector<const ResidualAnalysis*>> coloured, correlated;
  std::map<std::string, int> analysed;
  std::map<std::string, double> strong;  // output: the largest RMSE / noise where strong
  std::set<std::string> strong_and_correlated;  // outputs strong in an input-correlated run
  std::set<std::string> innovation_outputs, innovations_strong;  // the filter-error method
  for (const ResidualAnalysis& a : stage.residuals) {
    if (!a.tested() || a.noise_free || failed.count({a.experiment, a.output}) > 0) continue;
    if (analysed[a.output]++ == 0) outputs.push_back(a.output);
    if (a.coloured()) coloured[a.output].push_back(&a);
    if (a.input_correlated) correlated[a.output].push_back(&a);
    if (a.innovations) {
      // A filter's normalised innovations: their RMS is 1 by construction, so the strength is
      // in the colour alone, or in a correlation with the inputs (dynamics left out).
      if (a.coloured() && (a.lag1 > kStrongLag1 || a.input_correlated)) {
        strong[a.output] = std::max(strong[a.output], a.lag1);
        innovations_strong.insert(a.output);
      }
      innovation_outputs.insert(a.output);
      continue;
    }
    const auto m = metrics.find({a.experiment, a.output});
    if (a.coloured() && a.lag1 > kStrongLag1 && m != metrics.end() && m->second->noise > 0.0) {
      // What the residual would be without the noise on the measured inputs (its share from
      // the input noise refits): that part is noise, not structure the model leaves out.
      const double ratio = m->second->rmse * std::sqrt(1.0 - a.input_noise_share) / m->second->noise;
      if (ratio > kStrongNoiseRatio) {
        strong[a.output] = std::max(strong[a.output], ratio);
        if (a.input_correlated) strong_and_correlated.insert(a.output);
      }
    }
  }
  for (const std::string& output : outputs) {
    if (!coloured[output].empty()) {
      Finding f = MakeFinding(FindingKind::kColouredResiduals,
                              ColouredResidualWarning(stage.name, output, coloured[output],
                                                      analysed[output], stage.summary.uncertainty));
      f.stage = stage.name;
      f.output = output;
      f.count = static_cast<int>(coloured[output].size());
      double share = 0.0;  // the largest share of input noise among the coloured
      for (const ResidualAnalysis* a : coloured[output]) share = std::max(share, a->input_noise_share);
      if (share >= 0.1) {
        char text[200];
        std::snprintf(text, sizeof(text),
                      "; up to %.0f %% of the residual power is the noise on a measured input, "
                      "which the standard errors include",
                      100.0 * share);
        f.message += text;
      }
      if (innovation_outputs.count(output) > 0) {
        f.message = "the filter's innovations of " + output +
                    " are coloured: the disturbance model (noise:) does not explain all that "
                    "the ship model leaves" +
                    f.message.substr(f.message.find(" in "));
        if (innovations_strong.count(output) > 0) {
          f.message += "; strongly (lag-1 above 0.3, or correlated with the inputs): structure "
                       "remains that no noise model should absorb";
          f.severity = FindingSeverity::kWarning;
          f.value = strong[output];
          f.threshold = kStrongLag1;
        }
      } else if (strong.count(output) > 0) {
        char text[240];
        std::snprintf(text, sizeof(text),
                      "; the structure is strong (lag-1 above %.1f with an RMSE up to %.3g x the "
                      "record's noise level, beyond what input noise makes): the model leaves out "
                      "what drives the residual",
                      kStrongLag1, strong[output]);
        f.message += text;
        if (strong_and_correlated.count(output) == 0) {
          // Slow noise of the sensor itself (a compass's drift, an AR(1) of seconds) looks the
          // same and is not correlated with the inputs; the intervals then hold for neither.
          f.message += ", or the measurement's own noise is slow (a compass's or GNSS "
                       "heading's error of seconds to minutes): the residuals are not "
                       "correlated with the inputs beyond the band, as such noise leaves them; "
                       "either way the standard errors are too narrow (about 1.8x on the "
                       "independent corpus's compass-noise class)";
        }
        // The filter-error method tells the two apart (docs/models.md, noise: auto): on the
        // noise-structure corpus every correct record of sensor noise, waves, gusts and drift
        // so called was judged good under it.
        f.message += "; `noise: auto` on the stage identifies slow sensor noise, waves and "
                     "gusts with the ship and tells them from missing structure";
        f.severity = FindingSeverity::kWarning;
        f.value = strong[output];
        f.threshold = kStrongNoiseRatio;
      }
      findings->push_back(std::move(f));
    }
    if (!correlated[output].empty()) {
      Finding f = MakeFinding(
          FindingKind::kInputCorrelatedResiduals,
          InputCorrelatedResidualWarning(stage.name, output, correlated[output], analysed[output]));
      f.stage = stage.name;
      f.output = output;
      f.count = static_cast<int>(correlated[output].size());
      findings->push_back(std::move(f));
    }
  }
}

}  // namespace vesselid
