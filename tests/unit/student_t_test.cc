// Student's t quantiles against the published table values (two-sided 95 %: the 0.975
// quantile) and the normal limit.
#include "engine/base/student_t.h"

#include "gtest/gtest.h"

namespace vesselid {
namespace student_t_test {

TEST(StudentT, QuantilesMatchTheTable) {
  EXPECT_NEAR(StudentTQuantile(0.975, 1), 12.7062, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.975, 2), 4.3027, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.975, 7), 2.3646, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.975, 30), 2.0423, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.975, 1e6), 1.9600, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.025, 7), -2.3646, 1e-4);
  EXPECT_NEAR(StudentTQuantile(0.5, 3), 0.0, 1e-9);
  EXPECT_TRUE(std::isnan(StudentTQuantile(1.0, 3)));
  EXPECT_TRUE(std::isnan(StudentTQuantile(0.9, 0)));
}

}  // namespace student_t_test
}  // namespace vesselid
