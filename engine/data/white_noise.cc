#include "engine/data/white_noise.h"

#include <cmath>

#include "engine/base/statistics.h"

namespace vesselid {
namespace {

constexpr double kRatio = 1e-3;           // noise SD / signal SD below which noise is ignored
constexpr double kNormalMad = 0.6745;     // median |x| / SD of a normal variable
constexpr double kWhiteRatioLow = 0.8;    // third- over second-difference sigma: white noise 1
constexpr double kWhiteRatioHigh = 1.25;
constexpr double kRepeatShare = 0.2;      // share of exact repeats that marks a held input

}  // namespace

double WhiteInputNoise(const std::vector<double>& values) {
  const size_t n = values.size();
  if (n < 50) return 0.0;
  double mean = 0.0;
  int repeats = 0;
  for (size_t k = 0; k < n; ++k) {
    mean += values[k];
    if (k > 0 && values[k] == values[k - 1]) ++repeats;
  }
  if (repeats > kRepeatShare * (n - 1)) return 0.0;
  mean /= n;
  double variance = 0.0;
  for (double v : values) variance += (v - mean) * (v - mean);
  const double sd = std::sqrt(variance / n);
  // |second| and |third| differences: white noise of SD sigma gives them SDs sqrt(6) sigma and
  // sqrt(20) sigma; their medians (0.6745 SD for a normal variable) pass over the few large
  // ones a zigzag's corners or a step give.
  std::vector<double> second, third;
  second.reserve(n);
  third.reserve(n);
  for (size_t k = 2; k < n; ++k) {
    const double d2 = values[k] - 2.0 * values[k - 1] + values[k - 2];
    second.push_back(std::abs(d2));
    if (k >= 3) {
      third.push_back(std::abs(values[k] - 3.0 * values[k - 1] + 3.0 * values[k - 2] -
                               values[k - 3]));
    }
  }
  const double sigma = UpperMedian(second) / (kNormalMad * std::sqrt(6.0));
  const double sigma3 = UpperMedian(third) / (kNormalMad * std::sqrt(20.0));
  if (!(sigma >= kRatio * sd) || !(sigma > 0.0)) return 0.0;
  // White: the third differences see the same sigma. A signal smooth on the sampling scale
  // leaves a factor (omega dt) less in each higher difference (ratio far below 1).
  const double ratio = sigma3 / sigma;
  return ratio > kWhiteRatioLow && ratio < kWhiteRatioHigh ? sigma : 0.0;
}

}  // namespace vesselid
