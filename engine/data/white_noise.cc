#include "engine/data/white_noise.h"

#include <cmath>

#include "engine/base/statistics.h"

namespace vesselid {
namespace {

constexpr double kRatio = 1e-3;           // noise SD / signal SD below which noise is ignored
constexpr double kNormalMad = 0.6745;     // median |x| / SD of a normal variable
constexpr double kWhiteRatioLow = 0.8;    // third- over second-difference sigma: white noise 1
constexpr double kWhiteRatioHigh = 1.25;
constexpr size_t kMinWindows = 50;        // windows free of held samples needed to judge
constexpr double kMinLiveShare = 0.3;     // and their share of the samples

}  // namespace

double WhiteInputNoise(const std::vector<double>& values) {
  const size_t n = values.size();
  if (n < 50) return 0.0;
  // Held samples (equal to a neighbour: a zigzag's rudder held at its angle, a logger writing
  // exact zeros while the rudder rests, PWM levels) carry no noise; the differences are taken
  // over the stretches between them.
  std::vector<char> held(n, 0);
  for (size_t k = 1; k < n; ++k) {
    if (values[k] == values[k - 1]) held[k] = held[k - 1] = 1;
  }
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= n;
  double variance = 0.0;
  for (double v : values) variance += (v - mean) * (v - mean);
  const double sd = std::sqrt(variance / n);
  // |second| and |third| differences of windows free of held samples: white noise of SD sigma
  // gives them SDs sqrt(6) sigma and sqrt(20) sigma; their medians (0.6745 SD for a normal
  // variable) pass over the few large ones a zigzag's corners or a step give.
  std::vector<double> second, third;
  second.reserve(n);
  third.reserve(n);
  for (size_t k = 3; k < n; ++k) {
    if (held[k] || held[k - 1] || held[k - 2] || held[k - 3]) continue;
    second.push_back(std::abs(values[k] - 2.0 * values[k - 1] + values[k - 2]));
    third.push_back(
        std::abs(values[k] - 3.0 * values[k - 1] + 3.0 * values[k - 2] - values[k - 3]));
  }
  if (second.size() < kMinWindows || second.size() < kMinLiveShare * n) return 0.0;
  const double sigma = UpperMedian(second) / (kNormalMad * std::sqrt(6.0));
  const double sigma3 = UpperMedian(third) / (kNormalMad * std::sqrt(20.0));
  if (!(sigma >= kRatio * sd) || !(sigma > 0.0)) return 0.0;
  // White: the third differences see the same sigma. A signal smooth on the sampling scale
  // leaves a factor (omega dt) less in each higher difference (ratio far below 1).
  const double ratio = sigma3 / sigma;
  return ratio > kWhiteRatioLow && ratio < kWhiteRatioHigh ? sigma : 0.0;
}

}  // namespace vesselid
