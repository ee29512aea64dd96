// Min/max decimation of a sampled signal for plotting: the samples are cut into buckets of
// consecutive indices and each bucket keeps only its smallest and largest value (in index
// order), so that a line drawn through the kept samples covers the same vertical extent per
// bucket as the full signal (peaks and spikes are never lost) with at most `max_points`
// samples.
#pragma once

#include <cstddef>
#include <vector>

namespace vesselid {

// Indices (increasing) of the samples of `values` to keep, at most max(max_points, 2) of them;
// every index when values.size() <= max_points. The first and last samples are kept too when
// the budget allows (buckets then exclude them). Values should be finite.
std::vector<size_t> MinMaxDecimation(const std::vector<double>& values, size_t max_points);

}  // namespace vesselid
