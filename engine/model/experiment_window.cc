#include "engine/model/experiment_window.h"

#include <algorithm>

namespace vesselid {
namespace {

// Index of the last node at or before t_end, at least 1 (a problem needs two nodes).
int LastNodeIndex(const Experiment& e, double t_end) {
  const auto after = std::upper_bound(e.node_time.begin(), e.node_time.end(), t_end);
  const int last = static_cast<int>(after - e.node_time.begin()) - 1;
  return std::clamp(last, 1, e.num_nodes() - 1);
}

}  // namespace

double LastNodeUntil(const Experiment& experiment, double t_end) {
  return experiment.node_time[LastNodeIndex(experiment, t_end)];
}

Experiment ExperimentUntil(const Experiment& experiment, double t_end) {
  const int last = LastNodeIndex(experiment, t_end);
  if (last + 1 == experiment.num_nodes()) return experiment;
  Experiment e = experiment;
  const int nodes = last + 1;
  e.node_time.resize(nodes);
  e.node_substeps.resize(nodes - 1);
  e.node_step.resize(nodes - 1);
  e.node_first_sample.resize(nodes + 1);
  e.samples.resize(e.node_first_sample.back());
  int steps = 0;
  for (int s : e.node_substeps) steps += s;
  // Rows: start, midpoint and end of each step, then the inputs at the last node (the next
  // step's start row: the right limit there).
  e.input_cache.resize(static_cast<size_t>(3 * steps + 1) * e.num_inputs);
  for (InputCorrectionGrid& grid : e.input_corrections) {
    if (static_cast<int>(grid.step_interval.size()) > steps) grid.step_interval.resize(steps);
  }
  std::fill(e.output_sample_count.begin(), e.output_sample_count.end(), 0);
  for (const ExperimentSample& s : e.samples) ++e.output_sample_count[s.output];
  for (size_t o = 0; o < e.channel_noise_power.size(); ++o) {
    const int before = experiment.output_sample_count[o];
    if (before > 0) e.channel_noise_power[o] *= double(e.output_sample_count[o]) / before;
  }
  ++e.weights_revision;
  return e;
}

}  // namespace vesselid
