// Halton low-discrepancy points in the unit cube: coordinate k of point i is the radical
// inverse of i in the k-th prime base,
//
//   phi_b(i) = sum_j d_j b^-(j+1)   for i = sum_j d_j b^j,
//
// shifted by a seeded offset per coordinate (Cranley-Patterson rotation, z = phi + s mod 1)
// so that different seeds give different but equally even point sets. Deterministic: the
// shifts come from std::mt19937_64, whose output the C++ standard fixes.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "engine/base/check.h"

namespace vesselid {

class HaltonSequence {
 public:
  HaltonSequence(int dimension, uint64_t seed) : dimension_(dimension) {
    VESSELID_CHECK(dimension >= 1);
    for (uint64_t n = 2; static_cast<int>(primes_.size()) < dimension; ++n) {
      bool prime = true;
      for (uint64_t p : primes_) prime = prime && n % p != 0;
      if (prime) primes_.push_back(n);
    }
    std::mt19937_64 random(seed);
    for (int k = 0; k < dimension; ++k) shift_.push_back((random() >> 11) * 0x1.0p-53);
  }

  // Point i (i >= 1; point 0 of the plain sequence is the corner 0).
  std::vector<double> Point(uint64_t i) const {
    std::vector<double> z(dimension_);
    for (int k = 0; k < dimension_; ++k) {
      const double base = static_cast<double>(primes_[k]);
      double value = 0.0, weight = 1.0 / base;
      for (uint64_t n = i; n > 0; n /= primes_[k], weight /= base) value += (n % primes_[k]) * weight;
      value += shift_[k];
      z[k] = value >= 1.0 ? value - 1.0 : value;
    }
    return z;
  }

 private:
  int dimension_;
  std::vector<uint64_t> primes_;
  std::vector<double> shift_;
};

}  // namespace vesselid
