// Records that hold several trajectory segments told apart by a segment column (a campaign
// logged as one file, seed 000's 127 segments): each segment becomes its own experiment
// "<name>@<id>" with its own initial state, and a run may take a random share of them for
// training and the rest for validation.
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

struct SegmentSelection {
  std::string column;  // empty: the record is one experiment
  enum class Take { kAll, kTraining, kValidation };
  Take take = Take::kAll;
  double validation_share = 0.3;  // of the segments, drawn at random with `seed`
  unsigned seed = 1;
};

struct SegmentRange {
  long id = 0;
  double t_begin = 0.0, t_end = 0.0;  // first and last row of the segment
};

// The segments of `data` in time order, with the selection applied. Segment ids must be
// integers and each must occupy one contiguous block of rows.
bool SelectSegments(const Trajectory& data, const SegmentSelection& selection,
                    std::vector<SegmentRange>* segments, std::string* error);

// Splits ids 0..count-1 at random: the first round(share * count) of a seeded shuffle are the
// validation part. The same (count, share, seed) always gives the same split.
std::vector<bool> RandomValidationMask(int count, double share, unsigned seed);

bool StringToTake(const std::string& text, SegmentSelection::Take* take);

}  // namespace vesselid
