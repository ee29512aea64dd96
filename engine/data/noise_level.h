// Noise level of a sampled signal from the data alone: white noise of standard deviation sigma
// gives second differences y[k+1] - 2 y[k] + y[k-1] of variance 6 sigma^2, and a signal smooth
// on the sampling scale adds little, so sigma ~ sqrt(mean (second difference)^2 / 6).
#pragma once

#include <cmath>
#include <limits>

namespace vesselid {

class NoiseLevel {
 public:
  // `difference_wrap` maps a second difference (e.g. WrapAngle for a wrapped angle).
  template <class Wrap>
  void Add(double value, const Wrap& difference_wrap) {
    if (count_ >= 2) {
      const double d2 = difference_wrap(value - 2.0 * previous_[1] + previous_[0]);
      sum_ += d2 * d2;
    }
    previous_[0] = previous_[1];
    previous_[1] = value;
    ++count_;
  }
  void Add(double value) {
    Add(value, [](double d) { return d; });
  }
  // NaN with fewer than three values.
  double Sigma() const {
    return count_ >= 3 ? std::sqrt(sum_ / (count_ - 2) / 6.0)
                       : std::numeric_limits<double>::quiet_NaN();
  }
  int count() const { return count_; }

 private:
  int count_ = 0;
  double previous_[2] = {0.0, 0.0};
  double sum_ = 0.0;
};

}  // namespace vesselid
