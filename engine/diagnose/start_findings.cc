#include "engine/diagnose/start_findings.h"

#include <cmath>
#include <cstdio>

namespace vesselid {

void AddImplausibleStartFindings(const std::vector<ExperimentFit>& fits, const std::string& stage,
                                 const DisplayUnitOf& unit_of, std::vector<Finding>* findings) {
  for (const ExperimentFit& fit : fits) {
    const HeldOutStartReport& start = fit.start;
    const StartOffset* worst = nullptr;
    int beyond = 0;
    for (const StartOffset& o : start.offsets) {
      if (!(o.sds > start.implausible_sds)) continue;
      ++beyond;
      if (worst == nullptr || o.sds > worst->sds) worst = &o;
    }
    if (worst == nullptr) continue;
    const DisplayUnit unit = unit_of ? unit_of(fit.experiment, worst->state) : DisplayUnit{"", 1.0};
    const std::string u = unit.unit.empty() ? "" : " " + unit.unit;
    char text[512];
    std::snprintf(text, sizeof(text),
                  "held-out run '%s' is scored from a refitted start: %s %.4g%s against %.4g%s "
                  "measured (%.0f noise SDs%s)",
                  fit.experiment.c_str(), worst->state.c_str(), unit.scale * worst->refitted,
                  u.c_str(), unit.scale * worst->measured, u.c_str(), worst->sds,
                  beyond > 1 ? (", and " + std::to_string(beyond - 1) + " more state(s)").c_str()
                             : "");
    std::string message = text;
    // The run's own figures both ways, output by output.
    for (const ChannelMetrics& refitted : fit.channels) {
      for (const ChannelMetrics& measured : start.measured_start) {
        if (measured.output != refitted.output) continue;
        std::snprintf(text, sizeof(text), "; %s fit %.1f %% refitted, %.1f %% from the measured start",
                      refitted.output.c_str(), refitted.fit_percent, measured.fit_percent);
        message += text;
      }
    }
    if (start.measured_start_diverged) message += "; from the measured start it diverges";
    Finding f = MakeFinding(FindingKind::kImplausibleStart, message);
    f.stage = stage;
    f.experiment = fit.experiment;
    f.output = worst->state;
    f.value = worst->sds;
    f.threshold = start.implausible_sds;
    findings->push_back(std::move(f));
  }
}

}  // namespace vesselid
