// The held-out zigzag check on a list of zigzags made up for it: the interval is
// the held-out run's simulation plus the training errors' mean, +- t(0.975, n-1) s sqrt(1+1/n);
// a measurement outside it is called uncovered, and without held-out runs or with fewer than
// three training zigzags there is no interval, with a note saying why.
#include "engine/output/held_out_zigzags.h"

#include <cmath>

#include "engine/base/student_t.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace held_out_zigzags_test {

ZigzagEntry Zigzag(const std::string& experiment, bool held_out, double measured, double simulated,
                   const std::string& stage = "output_error") {
  ZigzagEntry z;
  z.stage = stage;
  z.experiment = experiment;
  z.held_out = held_out;
  z.rudder_deg = 10.0;
  z.heading_deg = 10.0;
  z.measured_first = measured;  // no second overshoot anywhere
  z.simulated_first = simulated;
  return z;
}

TEST(HeldOutZigzags, IntervalFromTheTrainingErrors) {
  // Training errors 0.5, -0.5, 1.0, 0.0: mean 0.25, SD sqrt(0.4167).
  const std::vector<ZigzagEntry> zigzags = {
      Zigzag("a", false, 5.5, 5.0),   Zigzag("b", false, 6.5, 7.0),
      Zigzag("c", false, 9.0, 8.0),   Zigzag("d", false, 4.0, 4.0),
      Zigzag("near", true, 10.5, 10.0, "final"), Zigzag("far", true, 14.0, 10.0, "final"),
      Zigzag("near", true, 0.0, 0.0)};
  const HeldOutZigzagCheck check = CheckHeldOutZigzags(zigzags);
  EXPECT_EQ(check.stage, "final");
  ASSERT_EQ(check.errors.size(), 1u);  // no second overshoot anywhere
  EXPECT_NE(check.note.find("second_overshoot: 0 training zigzags"), std::string::npos)
      << check.note;
  const double sd = std::sqrt((0.0625 + 0.5625 + 0.5625 + 0.0625) / 3.0);
  EXPECT_NEAR(check.errors[0].mean, 0.25, 1e-12);
  EXPECT_NEAR(check.errors[0].sd, sd, 1e-12);
  const double half = StudentTQuantile(0.975, 3) * sd * std::sqrt(1.25);
  ASSERT_EQ(check.rows.size(), 2u);
  EXPECT_NEAR(check.rows[0].low, 10.25 - half, 1e-12);
  EXPECT_NEAR(check.rows[0].high, 10.25 + half, 1e-12);
  EXPECT_TRUE(check.rows[0].covered);
  EXPECT_FALSE(check.rows[1].covered);
  EXPECT_EQ(check.errors[0].held_out, 2);
  EXPECT_EQ(check.errors[0].covered, 1);
  EXPECT_NE(HeldOutZigzagsText(check).find("covers 1 of 2 held-out runs"), std::string::npos)
      << HeldOutZigzagsText(check);
}

TEST(HeldOutZigzags, NoneWithoutHeldOutRuns) {
  const HeldOutZigzagCheck check =
      CheckHeldOutZigzags({Zigzag("a", false, 5.5, 5.0)});
  EXPECT_TRUE(check.rows.empty());
  EXPECT_EQ(check.note, "the run holds out no zigzag");
}

}  // namespace held_out_zigzags_test
}  // namespace vesselid
