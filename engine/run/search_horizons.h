// Segment lengths a stage's global start searches on (`global: {horizons: ...}`). From a far
// point a whole record of a turning vessel diverges or wraps its heading into a wrong basin;
// on short pieces it neither diverges nor wraps, so the multistart's points are judged on
// pieces they can simulate, and its best point is carried through longer pieces to the
// whole experiments (a continuation whose first phase takes the global start, continuation.h).
#pragma once

#include <vector>

#include "engine/model/experiment.h"

namespace vesselid {

struct SearchHorizons {
  // kAuto: AutomaticHorizons of the stage's experiments (the default); kGiven: `lengths`;
  // kNone: the search runs on the whole experiments.
  enum class Mode { kAuto, kGiven, kNone };
  Mode mode = Mode::kAuto;
  std::vector<double> lengths;  // s, increasing (kGiven)
};

// The automatic schedule: a sixth of the shortest experiment (at least 20 sample intervals),
// then three times longer while below half the longest; empty when even the first would
// not be shorter than half the shortest experiment (the experiments are short already).
std::vector<double> AutomaticHorizons(const std::vector<Experiment>& experiments);

}  // namespace vesselid
