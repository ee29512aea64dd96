#include "engine/output/held_out_start_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

std::string HeldOutStartSentence(const std::vector<ExperimentFit>& fits) {
  std::string mode;
  std::vector<std::string> estimated;
  double shortest = INFINITY, longest = 0.0;
  for (const ExperimentFit& fit : fits) {
    if (fit.start.mode.empty()) continue;
    mode = fit.start.mode;
    for (const std::string& name : fit.start.estimated) {
      if (std::find(estimated.begin(), estimated.end(), name) == estimated.end())
        estimated.push_back(name);
    }
    if (fit.start.burn_in > 0.0) {
      shortest = std::min(shortest, fit.start.burn_in);
      longest = std::max(longest, fit.start.burn_in);
    }
  }
  if (mode.empty()) return "";
  std::string names;
  for (const std::string& name : estimated) names += (names.empty() ? "" : ", ") + name;
  char burn_in[96] = "";
  if (longest > 0.0) {
    if (longest - shortest < 0.05 * longest)
      std::snprintf(burn_in, sizeof(burn_in), "%.3g s", longest);
    else
      std::snprintf(burn_in, sizeof(burn_in), "%.3g-%.3g s", shortest, longest);
  }
  const std::string what = names.empty() ? "" : names + " estimated on a burn-in of " +
                                                    burn_in + " at each run's start";
  if (mode == "measured") {
    return "Held-out runs are predicted from their measured start" +
           (what.empty() ? std::string(": nothing is estimated on them.")
                         : "; " + what + ", which is not scored (a run's own parameters "
                           "weighed against the training runs' spread).");
  }
  return "Held-out runs are scored from starts refitted on the whole run (held_out: {start: "
         "refitted}); the figures from the measured start (" +
         (what.empty() ? std::string("nothing estimated") : what + ", not scored") +
         ") are beside them.";
}

std::string HeldOutStartTable(const std::vector<ExperimentFit>& fits, const std::string& indent) {
  std::string text;
  char row[256];
  for (const ExperimentFit& fit : fits) {
    if (fit.start.mode != "refitted") continue;
    if (text.empty()) {
      std::snprintf(row, sizeof(row), "%s%-16s %-8s %12s %16s %14s\n", indent.c_str(), "run",
                    "output", "fit % refit", "fit % measured", "worst start");
      text += row;
    }
    const StartOffset* worst = nullptr;
    for (const StartOffset& o : fit.start.offsets) {
      if (std::isfinite(o.sds) && (worst == nullptr || o.sds > worst->sds)) worst = &o;
    }
    char offset[64] = "-";
    if (worst != nullptr) std::snprintf(offset, sizeof(offset), "%s %.0f SD", worst->state.c_str(), worst->sds);
    for (const ChannelMetrics& refitted : fit.channels) {
      char measured[32] = "-";
      if (fit.start.measured_start_diverged) std::snprintf(measured, sizeof(measured), "diverges");
      for (const ChannelMetrics& m : fit.start.measured_start) {
        if (m.output == refitted.output)
          std::snprintf(measured, sizeof(measured), "%.1f", m.fit_percent);
      }
      std::snprintf(row, sizeof(row), "%s%-16s %-8s %12.1f %16s %14s\n", indent.c_str(),
                    fit.experiment.c_str(), refitted.output.c_str(), refitted.fit_percent,
                    measured, offset);
      text += row;
    }
  }
  return text;
}

}  // namespace vesselid
