// The channels of one record, each extracted (ExtractChannel) and, for an angle, unwrapped
// once for all the experiments cut from it: every segment of a long record would otherwise
// copy whole columns for each of its outputs and inputs (a 195 000-row campaign of 110
// segments: some 1 300 column copies per preparation).
#pragma once

#include <map>
#include <utility>

#include "engine/base/angle.h"
#include "engine/data/trajectory.h"

namespace vesselid {

class RecordChannels {
 public:
  explicit RecordChannels(const Trajectory& trajectory) : trajectory_(&trajectory) {}

  const Trajectory& trajectory() const { return *trajectory_; }

  // The present samples of `column` (ExtractChannel).
  const Channel& Extracted(int column) {
    auto found = extracted_.find(column);
    if (found == extracted_.end()) {
      found = extracted_.emplace(column, ExtractChannel(*trajectory_, column)).first;
    }
    return found->second;
  }

  // Those samples unwrapped (UnwrapAngles), with the largest step between two of them.
  const Channel& Unwrapped(int column, double* largest_step) {
    auto found = unwrapped_.find(column);
    if (found == unwrapped_.end()) {
      Channel channel = Extracted(column);
      const double largest = UnwrapAngles(&channel.value);
      found = unwrapped_.emplace(column, std::make_pair(std::move(channel), largest)).first;
    }
    *largest_step = found->second.second;
    return found->second.first;
  }

 private:
  const Trajectory* trajectory_;
  std::map<int, Channel> extracted_;
  std::map<int, std::pair<Channel, double>> unwrapped_;
};

}  // namespace vesselid
