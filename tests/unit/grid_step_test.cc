// The equation-error grid's one step rule (regression_data.h): steps up to max_gap are
// accepted, a missing sample (2 or more median steps) is a gap to cut at, and a step between
// max_gap and 2 is row jitter. A resampled record's holes are whole multiples of the step, so
// with any max_gap they are accepted or cut, never refused.
#include "gtest/gtest.h"
#include "engine/regression/regression_data.h"

namespace vesselid {
namespace grid_step_test {

TEST(GridStep, AcceptedGapOrJitter) {
  EXPECT_EQ(GridStepOf(0.1, 0.1, 1.5), GridStep::kAccepted);
  EXPECT_EQ(GridStepOf(0.15, 0.1, 1.5), GridStep::kAccepted);
  EXPECT_EQ(GridStepOf(0.16, 0.1, 1.5), GridStep::kJitter);
  EXPECT_EQ(GridStepOf(0.16, 0.1, 2.0), GridStep::kAccepted);
  EXPECT_EQ(GridStepOf(0.2, 0.1, 1.5), GridStep::kGap);
  EXPECT_EQ(GridStepOf(11.0, 1.0, 3.0), GridStep::kGap);
  for (double max_gap : {1.0, 1.2, 1.5, 1.99, 2.0, 3.0, 7.5}) {
    for (int multiple = 1; multiple < 20; ++multiple) {
      const GridStep step = GridStepOf(multiple * 0.2, 0.2, max_gap);
      EXPECT_NE(step, GridStep::kJitter) << multiple << " steps, max_gap " << max_gap;
    }
  }
}

}  // namespace grid_step_test
}  // namespace vesselid
