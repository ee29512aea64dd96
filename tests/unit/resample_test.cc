// Resampling a jittered multi-rate log to a uniform grid (resample.h).
#include "engine/data/resample.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace resample_test {

// 10 Hz rows with +-30 ms jitter: a smooth output y = sin(0.5 t) + t, an angle output in
// radians crossing +-pi, and a command switched every 1.5 s logged on every third row.
Trajectory Log() {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  Trajectory data;
  data.names = {"y", "psi", "u"};
  data.columns.assign(3, {});
  for (int k = 0; k < 300; ++k) {
    const double t = 0.1 * k + jitter(random);
    data.t.push_back(t);
    data.line.push_back(k + 2);
    data.columns[0].push_back(std::sin(0.5 * t) + t);
    data.columns[1].push_back(std::remainder(3.0 + 0.4 * t, 2.0 * M_PI));
    data.columns[2].push_back(k % 3 == 0 ? std::floor(t / 1.5) : std::nan(""));
  }
  return data;
}

TEST(Resample, UniformGridInterpolatesOutputsAndHoldsInputs) {
  Trajectory data = Log();
  const Trajectory raw = data;
  ResampleOptions options;
  options.rate = 5.0;
  options.interpolated = {{"y", 0.0}, {"psi", 2.0 * M_PI}};
  ResampleReport report;
  std::string error;
  ASSERT_TRUE(Resample(options, 1000000, &data, &report, &error)) << error;
  EXPECT_EQ(report.rows_before, 300u);
  ASSERT_EQ(data.t.size(), report.rows_after);
  EXPECT_EQ(data.t.size(), static_cast<size_t>(std::floor((raw.t.back() - raw.t.front()) * 5)) + 1);
  for (size_t k = 0; k < data.t.size(); ++k) {
    EXPECT_EQ(data.t[k], raw.t.front() + k / 5.0);  // computed, not accumulated
    const double t = data.t[k];
    // Linear interpolation of a curve with |y''| <= 0.25 over <= 0.16 s: error <= 1e-3.
    EXPECT_NEAR(data.columns[0][k], std::sin(0.5 * t) + t, 1e-3) << t;
    // The angle is unwrapped first: no interpolation across the +-pi seam through 0.
    EXPECT_NEAR(std::remainder(data.columns[1][k] - (3.0 + 0.4 * t), 2.0 * M_PI), 0.0, 1e-9) << t;
    // The command held since its last logged sample (logged within 0.33 s of a switch).
    const double held = data.columns[2][k];
    EXPECT_TRUE(held == std::floor(t / 1.5) || held == std::floor(t / 1.5) - 1.0) << t;
  }
  EXPECT_TRUE(report.left_empty.empty());
}

TEST(Resample, LongGapsStayGaps) {
  Trajectory data = Log();
  for (int k = 100; k < 110; ++k) data.columns[0][k] = std::nan("");  // 1 s without y
  data.columns[0][200] = std::nan("");                                // one sample lost
  ResampleOptions options;
  options.rate = 10.0;
  options.max_gap = 3.0;
  options.interpolated = {{"y", 0.0}};
  ResampleReport report;
  std::string error;
  ASSERT_TRUE(Resample(options, 1000000, &data, &report, &error)) << error;
  ASSERT_EQ(report.left_empty.count("y"), 1u);
  // The grid points inside the 1.1 s gap (about 10) are empty; the single loss is bridged.
  EXPECT_GE(report.left_empty.at("y"), 9);
  EXPECT_LE(report.left_empty.at("y"), 12);
  int empty = 0;
  for (double v : data.columns[0]) empty += std::isnan(v);
  EXPECT_EQ(empty, report.left_empty.at("y"));
}

TEST(Resample, GapsOfTheLogAreEmptyInEveryColumn) {
  Trajectory data = Log();
  Trajectory cut;  // the logger off from t = 10 to 13 s
  cut.names = data.names;
  cut.columns.assign(3, {});
  for (size_t k = 0; k < data.t.size(); ++k) {
    if (data.t[k] > 10.0 && data.t[k] < 13.0) continue;
    cut.t.push_back(data.t[k]);
    for (int c = 0; c < 3; ++c) cut.columns[c].push_back(data.columns[c][k]);
  }
  ResampleOptions options;
  options.rate = 10.0;
  options.interpolated = {{"y", 0.0}};
  ResampleReport report;
  std::string error;
  ASSERT_TRUE(Resample(options, 1000000, &cut, &report, &error)) << error;
  EXPECT_GE(report.outside, 28);
  EXPECT_LE(report.outside, 31);
  EXPECT_TRUE(report.left_empty.empty());  // the log's gap is not the channel's
  for (size_t k = 0; k < cut.t.size(); ++k) {
    const bool off = cut.t[k] > 10.03 && cut.t[k] < 12.97;
    if (off) {
      EXPECT_TRUE(std::isnan(cut.columns[0][k]) && std::isnan(cut.columns[2][k])) << cut.t[k];
    }
    if (cut.t[k] < 9.9 || (cut.t[k] > 13.1 && cut.t[k] < 29.8)) {
      EXPECT_FALSE(std::isnan(cut.columns[2][k])) << cut.t[k];  // the held command
    }
  }
}

TEST(Resample, RefusesAGridPastTheLimit) {
  Trajectory data = Log();
  ResampleOptions options;
  options.rate = 1e6;
  ResampleReport report;
  std::string error;
  data.source = "log.csv";
  EXPECT_FALSE(Resample(options, 1000000, &data, &report, &error));
  EXPECT_NE(error.find("log.csv: resampling"), std::string::npos) << error;
}

}  // namespace resample_test
}  // namespace vesselid
