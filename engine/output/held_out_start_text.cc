#include "engine/output/held_out_start_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

namespace {

// Appends the names of `from` that `to` does not hold yet.
void AddNew(const std::vector<std::string>& from, std::vector<std::string>* to) {
  for (const std::string& name : from) {
    if (std::find(to->begin(), to->end(), name) == to->end()) to->push_back(name);
  }
}

std::string Joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

std::string HeldOutStartSentence(const std::vector<ExperimentFit>& fits) {
  std::string mode;
  std::vector<std::string> estimated, weighed, refitted;
  double shortest = INFINITY, longest = 0.0, requested = 0.0;
  bool changed = false;  // a configured burn_in held to its limits in some run
  for (const ExperimentFit& fit : fits) {
    const HeldOutStartReport& start = fit.start;
    if (start.mode.empty()) continue;
    mode = start.mode;
    AddNew(start.estimated, &estimated);
    AddNew(start.weighed, &weighed);
    AddNew(start.refitted, &refitted);
    if (start.burn_in > 0.0) {
      shortest = std::min(shortest, start.burn_in);
      longest = std::max(longest, start.burn_in);
      requested = start.requested_burn_in;
      changed |= requested > 0.0 && std::abs(start.burn_in - requested) > 0.01 * requested;
    }
  }
  if (mode.empty()) return "";
  char burn_in[160] = "";
  if (longest > 0.0) {
    if (longest - shortest < 0.05 * longest)
      std::snprintf(burn_in, sizeof(burn_in), "%.3g s", longest);
    else
      std::snprintf(burn_in, sizeof(burn_in), "%.3g-%.3g s", shortest, longest);
  }
  std::string what = estimated.empty() ? "" : Joined(estimated) + " estimated on a burn-in of " +
                                                  burn_in + " at each run's start";
  if (changed) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  " (burn_in %.6g s held to at least 10 sample intervals and at most half of "
                  "each run)",
                  requested);
    what += text;
  }
  const std::string weighing =
      weighed.empty() ? "" : "; " + Joined(weighed) + " weighed against the training runs' spread";
  if (mode == "measured") {
    return "Held-out runs are predicted from their measured start" +
           (what.empty() ? std::string(": nothing is estimated on them.")
                         : "; " + what + ", which is not scored" + weighing + ".");
  }
  return "Held-out runs are scored from starts refitted on the whole run (" +
         (refitted.empty() ? std::string("nothing") : Joined(refitted)) +
         "; held_out: {start: refitted}); the figures from the measured start (" +
         (what.empty() ? std::string("nothing estimated") : what + ", not scored" + weighing) +
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
