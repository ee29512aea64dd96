// Epoch times read without loss (time_base.h) through the CSV reader.
#include "engine/data/time_base.h"

#include <filesystem>
#include <fstream>

#include "engine/data/trajectory.h"
#include "gtest/gtest.h"
#include "tests/support/temp_file.h"

namespace vesselid {
namespace time_base_test {

namespace fs = std::filesystem;

using testing::WriteTemp;

TEST(TimeBase, ParsesDecimalTextExactlyInNanoseconds) {
  std::int64_t ns = 0;
  ASSERT_TRUE(ParseNanoseconds("1700000000.123", &ns));
  EXPECT_EQ(ns, 1700000000123000000LL);
  ASSERT_TRUE(ParseNanoseconds("1.7e9", &ns));
  EXPECT_EQ(ns, 1700000000000000000LL);
  ASSERT_TRUE(ParseNanoseconds("-2.5", &ns));
  EXPECT_EQ(ns, -2500000000LL);
  ASSERT_TRUE(ParseNanoseconds("+0.0000000015", &ns));  // 1.5 ns rounds away from zero
  EXPECT_EQ(ns, 2);
  ASSERT_TRUE(ParseNanoseconds("0.0000000014", &ns));
  EXPECT_EQ(ns, 1);
  ASSERT_TRUE(ParseNanoseconds("1700000000.1234567891234", &ns));  // beyond 19 digits: dropped
  EXPECT_EQ(ns, 1700000000123456789LL);
  ASSERT_TRUE(ParseNanoseconds("12.", &ns));
  EXPECT_EQ(ns, 12000000000LL);
  for (const char* bad : {"", "-", ".", "1e", "1.2.3", "abc", "1e400", "1e10", "nan", "1 2"}) {
    EXPECT_FALSE(ParseNanoseconds(bad, &ns)) << bad;
  }
  EXPECT_EQ(FormatNanoseconds(1700000000123000000LL), "1700000000.123");
  EXPECT_EQ(FormatNanoseconds(-2500000000LL), "-2.5");
  EXPECT_EQ(FormatNanoseconds(5000000000LL), "5");
  EXPECT_EQ(FormatUtc(1700000000123000000LL), "2023-11-14T22:13:20.123Z");
}

TEST(TimeBase, EpochTimesOneMillisecondApartStayExactlyOneMillisecondApart) {
  // As doubles, 1700000000.001 - 1700000000.000 is 0.00100016594 (spacing 2.4e-7 s there).
  ASSERT_NE(1700000000.001 - 1700000000.000, 0.001);
  const std::string path =
      WriteTemp("vesselid_epoch.csv",
                "t,a\n1700000000.000,1\n1700000000.001,2\n1700000000.002,3\n1700000123.457,4\n");
  Trajectory data;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(path, &data, &error)) << error;
  ASSERT_TRUE(data.epoch);
  EXPECT_EQ(data.time_origin_ns, 1700000000000000000LL);
  EXPECT_EQ(data.t[0], 0.0);
  EXPECT_EQ(data.t[1], 0.001);
  EXPECT_EQ(data.t[2] - data.t[1], 0.001);
  EXPECT_EQ(data.t[3], 123.457);
  EXPECT_EQ(data.line, (std::vector<int>{2, 3, 4, 5}));
}

TEST(TimeBase, EpochTimesMustIncreaseAtNanosecondResolution) {
  // Equal as doubles (both round to the same value), distinct as text: accepted in order.
  const std::string ok =
      WriteTemp("vesselid_epoch_close.csv", "t,a\n1700000000.0000001,1\n1700000000.0000002,2\n");
  Trajectory data;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(ok, &data, &error)) << error;
  EXPECT_EQ(data.t[1], 1e-7);
  const std::string back =
      WriteTemp("vesselid_epoch_back.csv", "t,a\n1700000000.002,1\n1700000000.001,2\n");
  EXPECT_FALSE(ReadTrajectoryCsv(back, &data, &error));
  EXPECT_NE(error.find(":3: time 1700000000.001 is not after the previous time 1700000000.002"),
            std::string::npos)
      << error;
}

TEST(TimeBase, EpochMillisecondsAreRefusedWithTheLine) {
  const std::string path = WriteTemp("vesselid_epoch_ms.csv", "t,a\n1700000000000,1\n");
  Trajectory data;
  std::string error;
  EXPECT_FALSE(ReadTrajectoryCsv(path, &data, &error));
  EXPECT_NE(error.find("vesselid_epoch_ms.csv:2: time 1700000000000 cannot be read to the "
                       "nanosecond"),
            std::string::npos)
      << error;
}

TEST(TimeBase, NamedTimeColumnAndRelativeTimesUnchanged) {
  CsvReadOptions options;
  options.time_column = "stamp";
  const std::string path = WriteTemp("vesselid_stamp.csv", "a,stamp\n1,0.1\n2,0.2\n");
  Trajectory data;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(path, options, &data, &error)) << error;
  EXPECT_FALSE(data.epoch);
  EXPECT_EQ(data.t, (std::vector<double>{0.1, 0.2}));  // as strtod reads them
  EXPECT_EQ(data.names, (std::vector<std::string>{"a"}));
  options.time_column = "time";
  EXPECT_FALSE(ReadTrajectoryCsv(path, options, &data, &error));
  EXPECT_NE(error.find("header has no time column 'time'"), std::string::npos) << error;
}

}  // namespace time_base_test
}  // namespace vesselid
