#include "engine/model/channel_weights.h"

#include <cmath>

namespace vesselid {

void SetChannelWeights(const std::vector<double>& weight, Experiment* experiment) {
  Experiment& e = *experiment;
  const size_t outputs = weight.size();
  if (e.channel_weight.size() < outputs) e.channel_weight.resize(outputs, 1.0);
  std::vector<double> factor(outputs, 1.0);
  double old_power = 0.0, new_power = 0.0;
  for (size_t c = 0; c < outputs; ++c) {
    const double old_weight = e.channel_weight[c];
    const bool usable = std::isfinite(weight[c]) && weight[c] > 0.0 && old_weight > 0.0;
    const double w = usable ? weight[c] : old_weight;
    factor[c] = usable ? w / old_weight : 1.0;
    const double power = c < e.channel_noise_power.size() ? e.channel_noise_power[c] : 0.0;
    old_power += power * old_weight * old_weight;
    new_power += power * w * w;
    e.channel_weight[c] = w;
  }
  for (ExperimentSample& s : e.samples) {
    if (s.output >= 0 && static_cast<size_t>(s.output) < outputs) s.weight *= factor[s.output];
  }
  ++e.weights_revision;
  if (old_power > 0.0 && new_power > 0.0) e.prior_weight *= std::sqrt(new_power / old_power);
}

}  // namespace vesselid
