// Experiments cut to the stretches where their inputs lie inside configured ranges.
#include "engine/model/input_range.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace input_range_test {

// Throttle 0.2 for t in [0, 50), 0.9 for [50, 80), 0.4 for [80, 200], sampled every second.
Trajectory Record() {
  Trajectory data;
  data.source = "record.csv";
  data.names = {"throttle"};
  data.columns.resize(1);
  for (int k = 0; k <= 200; ++k) {
    data.t.push_back(k);
    data.columns[0].push_back(k < 50 ? 0.2 : k < 80 ? 0.9 : 0.4);
  }
  return data;
}

ExperimentSpec Spec() {
  ExperimentSpec spec;
  spec.name = "steps";
  spec.inputs = {{"tau_m", "throttle"}};
  spec.input_range = {{"tau_m", {0.0, 0.6}}};
  return spec;
}

TEST(InputRange, CutsTheRecordIntoStretchesInsideTheRange) {
  std::vector<ExperimentSpec> pieces;
  std::string error;
  ASSERT_TRUE(SplitByInputRange(Spec(), Record(), &pieces, &error)) << error;
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].name, "steps#1");
  EXPECT_EQ(pieces[0].t_begin, 0.0);
  EXPECT_EQ(pieces[0].t_end, 49.0);
  EXPECT_EQ(pieces[1].name, "steps#2");
  EXPECT_EQ(pieces[1].t_begin, 80.0);
  EXPECT_EQ(pieces[1].t_end, 200.0);
  EXPECT_TRUE(pieces[1].input_range.empty());
}

TEST(InputRange, SkipsTheStartAfterLeavingTheRangeAndDropsShortStretches) {
  ExperimentSpec spec = Spec();
  spec.input_range_skip = 30.0;
  spec.input_range_min_duration = 60.0;
  std::vector<ExperimentSpec> pieces;
  std::string error;
  ASSERT_TRUE(SplitByInputRange(spec, Record(), &pieces, &error)) << error;
  // [0, 49] is shorter than 60 s; [80, 200] starts 30 s later.
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].t_begin, 110.0);
  EXPECT_EQ(pieces[0].t_end, 200.0);
}

TEST(InputRange, RespectsTheWindowAndNamesAnUnmappedInput) {
  ExperimentSpec spec = Spec();
  spec.t_begin = 100.0;
  std::vector<ExperimentSpec> pieces;
  std::string error;
  ASSERT_TRUE(SplitByInputRange(spec, Record(), &pieces, &error)) << error;
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].t_begin, 100.0);
  spec.inputs.clear();
  pieces.clear();
  EXPECT_FALSE(SplitByInputRange(spec, Record(), &pieces, &error));
  EXPECT_NE(error.find("input_range names input 'tau_m'"), std::string::npos) << error;
}

}  // namespace input_range_test
}  // namespace vesselid
