// The outlier rule (OutlierLimit, run_config.h): a robust limit over the runs' RMS costs with a
// floor of twice the median, so that runs whose costs are all alike name none.
#include <vector>

#include "engine/run/run_config.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace outlier_limit_test {

// Five runs within 3.5 % of each other: their MAD is tiny, median + 5 MAD is 1.09 x the
// median; none of them is an outlier.
TEST(OutlierLimit, RunsAllAlikeNameNone) {
  const std::vector<double> rms = {1.000, 1.012, 1.020, 1.028, 1.035};
  const double limit = OutlierLimit(rms, 5.0);
  EXPECT_DOUBLE_EQ(limit, 2.0 * 1.020);
  for (double r : rms) EXPECT_LT(r, limit);
}

// One run three times the others' cost is named, by the robust term or the floor.
TEST(OutlierLimit, ARunFarWorseIsNamed) {
  const std::vector<double> rms = {1.0, 1.1, 0.9, 1.05, 3.0};
  const double limit = OutlierLimit(rms, 5.0);
  EXPECT_GT(3.0, limit);
  EXPECT_LT(1.1, limit);
  // Widely spread costs: the robust term lies above the floor.
  const std::vector<double> spread = {1.0, 2.0, 3.0, 4.0, 20.0};
  EXPECT_DOUBLE_EQ(OutlierLimit(spread, 5.0), 3.0 + 5.0 * 1.4826 * 1.0);
}

}  // namespace outlier_limit_test
}  // namespace vesselid
