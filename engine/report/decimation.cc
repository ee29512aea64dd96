#include "engine/report/decimation.h"

#include <algorithm>

namespace vesselid {
namespace {

// Appends the indices of the minimum and the maximum of values[begin, end) in index order.
void KeepExtremes(const std::vector<double>& values, size_t begin, size_t end,
                  std::vector<size_t>* kept) {
  if (begin >= end) return;
  size_t low = begin, high = begin;
  for (size_t k = begin + 1; k < end; ++k) {
    if (values[k] < values[low]) low = k;
    if (values[k] > values[high]) high = k;
  }
  kept->push_back(std::min(low, high));
  if (low != high) kept->push_back(std::max(low, high));
}

}  // namespace

std::vector<size_t> MinMaxDecimation(const std::vector<double>& values, size_t max_points) {
  const size_t n = values.size();
  std::vector<size_t> kept;
  if (n <= max_points) {
    kept.resize(n);
    for (size_t k = 0; k < n; ++k) kept[k] = k;
    return kept;
  }
  if (max_points < 4) {
    KeepExtremes(values, 0, n, &kept);
    return kept;
  }
  // First and last sample, then (max_points - 2) / 2 buckets of equal share over the rest.
  const size_t buckets = (max_points - 2) / 2;
  const size_t inner = n - 2;
  kept.reserve(2 * buckets + 2);
  kept.push_back(0);
  for (size_t b = 0; b < buckets; ++b) {
    KeepExtremes(values, 1 + b * inner / buckets, 1 + (b + 1) * inner / buckets, &kept);
  }
  kept.push_back(n - 1);
  return kept;
}

}  // namespace vesselid
