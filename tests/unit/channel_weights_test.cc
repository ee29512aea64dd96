// Channel re-weighting (channel_weights.h): per-sample factors stay, each channel's samples
// take the new channel weight, and the initial-state prior keeps counting as one sample of
// the weighted noise level.
#include "engine/model/channel_weights.h"

#include <cmath>
#include <limits>

#include "gtest/gtest.h"

namespace vesselid {
namespace channel_weights_test {

Experiment TwoChannels() {
  Experiment e;
  // Output 0 (a position, noise 0.02) and output 2 (a heading, noise 0.005); output 1 not
  // compared. Weights: configured 1 and 4, times a per-sample factor 0.5 (e.g. length).
  e.samples = {{0, 1.0, 0.5}, {2, 0.1, 2.0}, {0, 1.1, 0.5}, {2, 0.2, 2.0}};
  e.channel_weight = {1.0, 1.0, 4.0};
  e.channel_noise_power = {2 * 0.02 * 0.02, 0.0, 2 * 0.005 * 0.005};
  // prior weight = 0.5 sqrt(sum P_c w_c^2 / count)
  e.prior_weight =
      0.5 * std::sqrt((2 * 0.02 * 0.02 * 1.0 + 2 * 0.005 * 0.005 * 16.0) / 4.0);
  return e;
}

TEST(ChannelWeights, SamplesTakeTheNewChannelWeightAndKeepTheirOwnFactor) {
  Experiment e = TwoChannels();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SetChannelWeights({1.0 / 0.02, nan, 1.0 / 0.005}, &e);
  EXPECT_DOUBLE_EQ(e.samples[0].weight, 0.5 / 0.02);
  EXPECT_DOUBLE_EQ(e.samples[1].weight, 0.5 / 0.005);
  EXPECT_DOUBLE_EQ(e.samples[2].weight, 0.5 / 0.02);
  EXPECT_DOUBLE_EQ(e.samples[3].weight, 0.5 / 0.005);
  EXPECT_DOUBLE_EQ(e.channel_weight[0], 50.0);
  EXPECT_DOUBLE_EQ(e.channel_weight[1], 1.0);  // NaN: kept
  EXPECT_DOUBLE_EQ(e.channel_weight[2], 200.0);
  // Noise levels that match the weights: the weighted noise level is 1 (x the factor 0.5).
  EXPECT_NEAR(e.prior_weight, 0.5, 1e-12);
  // Applying the same weights again changes nothing.
  const Experiment once = e;
  SetChannelWeights({1.0 / 0.02, nan, 1.0 / 0.005}, &e);
  for (size_t i = 0; i < e.samples.size(); ++i) {
    EXPECT_DOUBLE_EQ(e.samples[i].weight, once.samples[i].weight);
  }
  EXPECT_DOUBLE_EQ(e.prior_weight, once.prior_weight);
}

TEST(ChannelWeights, ZeroOrNegativeWeightsAreIgnored) {
  Experiment e = TwoChannels();
  const Experiment before = e;
  SetChannelWeights({0.0, 1.0, -3.0}, &e);
  for (size_t i = 0; i < e.samples.size(); ++i) {
    EXPECT_DOUBLE_EQ(e.samples[i].weight, before.samples[i].weight);
  }
  EXPECT_DOUBLE_EQ(e.prior_weight, before.prior_weight);
}

}  // namespace channel_weights_test
}  // namespace vesselid
