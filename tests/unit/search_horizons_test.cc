// The automatic pieces a stage's multistart searches on (engine/run/search_horizons.h).
#include "engine/run/search_horizons.h"

#include "gtest/gtest.h"

namespace vesselid {
namespace search_horizons_test {

Experiment Record(double duration, double interval) {
  Experiment e;
  for (double t = 0.0; t <= duration + 1e-9; t += interval) e.node_time.push_back(t);
  return e;
}

TEST(SearchHorizons, ASixthOfTheShortestThenThreeTimesLongerBelowHalfTheLongest) {
  const std::vector<double> lengths = AutomaticHorizons({Record(40, 0.1), Record(60, 0.1)});
  ASSERT_EQ(lengths.size(), 2u);
  EXPECT_NEAR(lengths[0], 40.0 / 6.0, 1e-9);
  EXPECT_NEAR(lengths[1], 20.0, 1e-9);  // 60 would not be below half of 60 s
}

TEST(SearchHorizons, AtLeastTwentySampleIntervals) {
  const std::vector<double> lengths = AutomaticHorizons({Record(300, 1.0)});
  ASSERT_FALSE(lengths.empty());
  EXPECT_NEAR(lengths[0], 50.0, 1e-9);  // 300 / 6 > 20 s
  const std::vector<double> coarse = AutomaticHorizons({Record(100, 2.0), Record(900, 2.0)});
  ASSERT_FALSE(coarse.empty());
  EXPECT_NEAR(coarse[0], 40.0, 1e-9);  // 20 intervals of 2 s > 100 / 6
  EXPECT_NEAR(coarse.back(), 360.0, 1e-9);  // 40, 120, 360 < 450
}

TEST(SearchHorizons, ShortRecordsAreSearchedWhole) {
  // 20 intervals of 0.5 s = 10 s is not below half of a 15 s record.
  EXPECT_TRUE(AutomaticHorizons({Record(15, 0.5)}).empty());
  EXPECT_TRUE(AutomaticHorizons({}).empty());
}

}  // namespace search_horizons_test
}  // namespace vesselid
