// The first part of a prepared experiment: a held-out run's burn-in, on which its unmeasured
// initial states and its own parameters are estimated before the rest is predicted.
#pragma once

#include "engine/model/experiment.h"

namespace vesselid {

// `experiment` up to its last node at or before t_end (at least its first two nodes): the
// nodes, their samples, the input cache's rows and the input corrections' steps up to there;
// the sample weights as they were (the burn-in's cost is a part of the whole run's).
Experiment ExperimentUntil(const Experiment& experiment, double t_end);

// Time of the last node of `experiment` at or before t_end (its second node at the earliest).
double LastNodeUntil(const Experiment& experiment, double t_end);

}  // namespace vesselid
