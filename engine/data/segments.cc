#include "engine/data/segments.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>

namespace vesselid {

std::vector<bool> RandomValidationMask(int count, double share, unsigned seed) {
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 random(seed);
  // Fisher-Yates with our own draws: std::shuffle's sequence is library-specific.
  for (int i = count - 1; i > 0; --i) {
    std::swap(order[i], order[random() % static_cast<unsigned>(i + 1)]);
  }
  std::vector<bool> validation(count, false);
  const int n = static_cast<int>(std::lround(share * count));
  for (int i = 0; i < n && i < count; ++i) validation[order[i]] = true;
  return validation;
}

bool StringToTake(const std::string& text, SegmentSelection::Take* take) {
  if (text == "all") *take = SegmentSelection::Take::kAll;
  else if (text == "training") *take = SegmentSelection::Take::kTraining;
  else if (text == "validation") *take = SegmentSelection::Take::kValidation;
  else return false;
  return true;
}

bool SelectSegments(const Trajectory& data, const SegmentSelection& selection,
                    std::vector<SegmentRange>* segments, std::string* error) {
  segments->clear();
  const int column = data.Find(selection.column);
  if (column < 0) {
    *error = data.source + ": no segment column '" + selection.column + "'";
    return false;
  }
  const std::vector<double>& ids = data.columns[column];
  std::set<long> seen;
  for (size_t k = 0; k < ids.size(); ++k) {
    const double value = ids[k];
    if (std::isnan(value)) continue;
    if (value != std::round(value)) {
      *error = data.source + ": row at t = " + std::to_string(data.t[k]) + ": segment id " +
               std::to_string(value) + " is not an integer";
      return false;
    }
    const long id = std::lround(value);
    if (!segments->empty() && segments->back().id == id) {
      segments->back().t_end = data.t[k];
      continue;
    }
    if (!seen.insert(id).second) {
      *error = data.source + ": segment " + std::to_string(id) +
               " resumes at t = " + std::to_string(data.t[k]) + " after another segment";
      return false;
    }
    segments->push_back({id, data.t[k], data.t[k]});
  }
  if (segments->empty()) {
    *error = data.source + ": segment column '" + selection.column + "' is empty";
    return false;
  }
  if (selection.take == SegmentSelection::Take::kAll) return true;
  const std::vector<bool> validation = RandomValidationMask(
      static_cast<int>(segments->size()), selection.validation_share, selection.seed);
  const bool want = selection.take == SegmentSelection::Take::kValidation;
  std::vector<SegmentRange> kept;
  for (size_t i = 0; i < segments->size(); ++i) {
    if (validation[i] == want) kept.push_back((*segments)[i]);
  }
  *segments = std::move(kept);
  return true;
}

}  // namespace vesselid
