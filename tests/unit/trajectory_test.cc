// CSV reading and input interpolation.
#include "engine/data/trajectory.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <filesystem>
#include <fstream>

#include "engine/data/interpolation.h"
#include "gtest/gtest.h"
#include "tests/support/temp_file.h"

namespace vesselid {
namespace trajectory_test {

namespace fs = std::filesystem;

using testing::WriteTemp;

TEST(Trajectory, ReadsMultiRateChannelsWithMissingSamples) {
  const std::string path = WriteTemp(
      "vesselid_multirate.csv", "t, gnss_n ,heading\n0,1.0,0.1\n0.1,,0.2\n0.2,3.0,\n0.3,,0.4\n");
  Trajectory t;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(path, &t, &error)) << error;
  ASSERT_EQ(t.names, (std::vector<std::string>{"gnss_n", "heading"}));
  Channel gnss = ExtractChannel(t, t.Find("gnss_n"));
  EXPECT_EQ(gnss.t, (std::vector<double>{0.0, 0.2}));
  EXPECT_EQ(gnss.value, (std::vector<double>{1.0, 3.0}));
  Channel heading = ExtractChannel(t, t.Find("heading"));
  EXPECT_EQ(heading.t.size(), 3u);
  EXPECT_EQ(t.Find("missing"), -1);
}

// Only the columns read must be numbers: unnamed and unlisted columns are skipped unread (a
// duplicate among them is no error), and a mangled cell of a read column is a missing sample
// counted with its row's time and line, whichever side of the time column it lies on.
TEST(Trajectory, ReadsOnlyTheListedColumnsAndCountsMangledCells) {
  std::string text = ",a,t,stamp,stamp,b\n";
  for (int k = 0; k < 40; ++k) {
    const std::string a = k == 7 ? "jan.68" : std::to_string(k);
    const std::string b = k == 9 || k == 30 ? "#REF!" : std::to_string(2 * k);
    text += std::to_string(k) + "," + a + "," + std::to_string(0.5 * k) + ",10:00:0" +
            std::to_string(k % 10) + ",x," + b + "\n";
  }
  const std::string path = WriteTemp("vesselid_listed.csv", text);
  CsvReadOptions options;
  options.columns = {"a", "b"};
  options.max_bad_share = 0.06;
  options.parallel_bytes = 1;  // the block reader too: it hands a mangled file to the sequential
  Trajectory t;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(path, options, &t, &error)) << error;
  EXPECT_EQ(t.names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(t.skipped_columns, (std::vector<std::string>{"", "stamp", "stamp"}));
  ASSERT_EQ(t.bad_cells.size(), 2u);
  EXPECT_EQ(t.bad_cells[0].column, "a");
  EXPECT_EQ(t.bad_cells[0].count, 1);
  EXPECT_EQ(t.bad_cells[0].times, (std::vector<double>{3.5}));
  EXPECT_EQ(t.bad_cells[0].lines, (std::vector<int>{9}));
  EXPECT_EQ(t.bad_cells[0].first_text, "jan.68");
  EXPECT_EQ(t.bad_cells[1].count, 2);
  EXPECT_EQ(t.bad_cells[1].times, (std::vector<double>{4.5, 15.0}));
  EXPECT_TRUE(std::isnan(t.columns[0][7]));
  EXPECT_EQ(t.columns[1][8], 16.0);
  // Above the share, refused at the first mangled cell of the column with the count.
  options.max_bad_share = 0.04;
  EXPECT_FALSE(ReadTrajectoryCsv(path, options, &t, &error));
  EXPECT_NE(error.find(":11: column 'b': '#REF!' is not a finite number (2 of the column's 40 "
                       "cells"),
            std::string::npos)
      << error;
  // Every column read (none listed): the text column refuses the file, as do any mangled
  // cells where none are accepted.
  options.columns.clear();
  options.max_bad_share = 0.0;
  EXPECT_FALSE(ReadTrajectoryCsv(path, options, &t, &error));
  EXPECT_NE(error.find("duplicate column 'stamp'"), std::string::npos) << error;
}

TEST(Trajectory, RejectsMissingTimeColumnAndDuplicates) {
  Trajectory t;
  std::string error;
  EXPECT_FALSE(ReadTrajectoryCsv(WriteTemp("vesselid_not.csv", "time,a\n0,1\n1,2\n"), &t, &error));
  EXPECT_NE(error.find(":1: header has no time column 't'"), std::string::npos) << error;
  EXPECT_FALSE(
      ReadTrajectoryCsv(WriteTemp("vesselid_dup.csv", "t,a,a\n0,1,1\n1,2,2\n"), &t, &error));
  EXPECT_NE(error.find("duplicate column 'a'"), std::string::npos) << error;
  EXPECT_FALSE(ReadTrajectoryCsv(WriteTemp("vesselid_inf.csv", "t,a\n0,1\n1,inf\n"), &t, &error));
  EXPECT_NE(error.find(":3: column 'a': 'inf' is not a finite number"), std::string::npos) << error;
  EXPECT_FALSE(ReadTrajectoryCsv(WriteTemp("vesselid_empty.csv", ""), &t, &error));
  EXPECT_NE(error.find("empty file"), std::string::npos) << error;
}

// The reader parses lines in place inside blocks of the file: lines that straddle a block
// boundary, CRLF endings, padded and missing fields, a last line without a newline and an
// error line far into the file read as a line-by-line reading would.
TEST(Trajectory, ReadsLinesAcrossBlocksAsWritten) {
  std::string text = "\xEF\xBB\xBF t ,heading, rate\r\n";
  std::vector<double> heading, rate;
  const int rows = 40000;  // about 1 MB: several read blocks
  for (int k = 0; k < rows; ++k) {
    heading.push_back(std::sin(0.001 * k) * 1e3 + 1e-7 * k);
    rate.push_back(k % 7 == 0 ? std::nan("") : -1.25e-3 * k);
    char line[128];
    std::snprintf(line, sizeof(line), "%.6f, %.17g ,%s%s", 0.05 * k, heading.back(),
                  std::isnan(rate.back()) ? "" : std::to_string(rate.back()).c_str(),
                  k + 1 == rows ? "" : (k % 3 == 0 ? "\r\n" : "\n"));
    text += line;
    if (!std::isnan(rate.back())) rate.back() = std::stod(std::to_string(rate.back()));
  }
  const std::string path = WriteTemp("vesselid_blocks.csv", text);
  Trajectory t;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(path, &t, &error)) << error;
  ASSERT_EQ(t.names, (std::vector<std::string>{"heading", "rate"}));
  ASSERT_EQ(t.t.size(), static_cast<size_t>(rows));
  for (int k = 0; k < rows; ++k) {
    ASSERT_EQ(t.columns[0][k], heading[k]) << k;
    if (std::isnan(rate[k])) {
      ASSERT_TRUE(std::isnan(t.columns[1][k])) << k;
    } else {
      ASSERT_EQ(t.columns[1][k], rate[k]) << k;
    }
    ASSERT_EQ(t.line[k], k + 2);
  }
  // A bad field on the last line, which has no newline, names its line.
  text += "\n2000.0,1x,2";
  EXPECT_FALSE(ReadTrajectoryCsv(WriteTemp("vesselid_blocks_bad.csv", text), &t, &error));
  EXPECT_NE(error.find(":" + std::to_string(rows + 2) + ": column 'heading': '1x' is not a "
                       "finite number"),
            std::string::npos)
      << error;
}

// Files past CsvReadOptions::parallel_bytes are parsed in blocks on several threads: the
// same trajectory as the sequential reader, to the bit, line numbers included (blank lines,
// CRLF, padded and missing fields, epoch times, no final newline), and the same message,
// naming the same line, for each thing it rejects anywhere in the file.
TEST(Trajectory, ParallelBlocksReadWhatTheSequentialReaderReads) {
  auto read = [](const std::string& text, bool parallel, Trajectory* t, std::string* error) {
    CsvReadOptions options;
    options.parallel_bytes = parallel ? 0 : std::numeric_limits<std::uint64_t>::max();
    options.max_values = 3 * 50000;
    return ReadTrajectoryCsv(WriteTemp("vesselid_parallel.csv", text), options, t, error);
  };
  for (const double origin : {0.0, 1.7e9}) {  // relative and epoch times
    std::string text = "\n t ,heading, rate\r\n";
    const int rows = 30000;
    for (int k = 0; k < rows; ++k) {
      char line[160];
      std::snprintf(line, sizeof(line), "%.3f, %.17g ,%s%s%s", origin + 0.05 * k,
                    std::sin(0.001 * k) * 1e3, k % 7 == 0 ? "" : std::to_string(-1e-3 * k).c_str(),
                    k % 101 == 0 ? "\n  \n" : "", k + 1 == rows ? "" : (k % 3 == 0 ? "\r\n" : "\n"));
      text += line;
    }
    Trajectory sequential, parallel;
    std::string error;
    ASSERT_TRUE(read(text, false, &sequential, &error)) << error;
    ASSERT_TRUE(read(text, true, &parallel, &error)) << error;
    EXPECT_EQ(parallel.names, sequential.names);
    EXPECT_EQ(parallel.t, sequential.t);
    EXPECT_EQ(parallel.line, sequential.line);
    EXPECT_EQ(parallel.epoch, sequential.epoch);
    EXPECT_EQ(parallel.time_origin_ns, sequential.time_origin_ns);
    ASSERT_EQ(parallel.columns.size(), 2u);
    for (int c = 0; c < 2; ++c) {
      ASSERT_EQ(parallel.columns[c].size(), sequential.columns[c].size());
      for (size_t k = 0; k < parallel.columns[c].size(); ++k) {
        ASSERT_EQ(std::isnan(parallel.columns[c][k]), std::isnan(sequential.columns[c][k]));
        if (!std::isnan(parallel.columns[c][k])) {
          ASSERT_EQ(parallel.columns[c][k], sequential.columns[c][k]);
        }
      }
    }
    EXPECT_EQ(sequential.line.back(), rows + 2 + 2 * (rows / 101 + 1));  // blank lines too
    // Each defect at a few places: early, at about a block's edge, late.
    const auto lines_at = [&](int k) {
      size_t at = 0;
      for (int n = 0; n < k; ++n) at = text.find('\n', at) + 1;
      return at;
    };
    for (int k : {5, 3751, 3752, 7500, 22222}) {
      const size_t at = lines_at(k), end = text.find('\n', at);
      const std::string line = text.substr(at, end - at);
      for (const std::string& bad :
           {std::string("1.0,1x,2"), std::string("1,2"), line + ",3", std::string("0,1,2"),
            std::string(",1,2"), std::string("5,1e200,2")}) {
        std::string defective = text;
        defective.replace(at, end - at, bad);
        std::string sequential_error, parallel_error;
        Trajectory ignored;
        ASSERT_FALSE(read(defective, false, &ignored, &sequential_error)) << bad;
        ASSERT_FALSE(read(defective, true, &ignored, &parallel_error)) << bad;
        EXPECT_EQ(parallel_error, sequential_error);
      }
    }
    // Too many values (rows x columns) for limits.data_values.
    std::string longer = text;
    for (int k = 0; k < 25000; ++k) longer += "\n" + std::to_string(origin + 2000.0 + k) + ",1,2";
    std::string sequential_error, parallel_error;
    Trajectory ignored;
    ASSERT_FALSE(read(longer, false, &ignored, &sequential_error));
    ASSERT_FALSE(read(longer, true, &ignored, &parallel_error));
    EXPECT_EQ(parallel_error, sequential_error);
    EXPECT_NE(sequential_error.find("limits.data_values"), std::string::npos) << sequential_error;
  }
}

// Traces are formatted in blocks of rows on several threads: the file holds every row once,
// in order, as %.10g (t) and %.12g (channels) with NaN as an empty field.
TEST(Trajectory, WritesEveryRowInOrderFromParallelBlocks) {
  Trajectory trace;
  trace.names = {"psi_measured", "psi_simulated"};
  trace.columns.resize(2);
  const int rows = 20000;  // several blocks
  for (int k = 0; k < rows; ++k) {
    trace.t.push_back(0.02 * k);
    trace.columns[0].push_back(k % 5 == 0 ? std::nan("") : std::sin(1e-3 * k) / 3.0);
    trace.columns[1].push_back(-1e5 * std::cos(1e-3 * k) / 7.0);
  }
  const std::string path =
      (fs::temp_directory_path() / "vesselid_trace_blocks.csv").string();
  std::string error;
  ASSERT_TRUE(WriteTrajectoryCsv(path, trace, &error)) << error;
  Trajectory read;
  ASSERT_TRUE(ReadTrajectoryCsv(path, &read, &error)) << error;
  ASSERT_EQ(read.names, trace.names);
  ASSERT_EQ(read.t.size(), trace.t.size());
  auto printed = [](double value, int digits) {
    char text[40];
    std::snprintf(text, sizeof(text), "%.*g", digits, value);
    return std::stod(text);
  };
  for (int k = 0; k < rows; ++k) {
    ASSERT_EQ(read.t[k], printed(trace.t[k], 10)) << k;
    ASSERT_EQ(std::isnan(read.columns[0][k]), std::isnan(trace.columns[0][k])) << k;
    if (!std::isnan(trace.columns[0][k])) {
      ASSERT_EQ(read.columns[0][k], printed(trace.columns[0][k], 12)) << k;
    }
    ASSERT_EQ(read.columns[1][k], printed(trace.columns[1][k], 12)) << k;
  }
}

Channel Sampled(double (*f)(double), double dt, int n) {
  Channel c;
  for (int k = 0; k < n; ++k) {
    c.t.push_back(k * dt);
    c.value.push_back(f(k * dt));
  }
  return c;
}

TEST(Interpolation, ZeroOrderHoldLinearAndEnds) {
  Channel c{{0.0, 1.0, 2.0}, {0.0, 10.0, 20.0}};
  std::vector<double> t = {-1.0, 0.5, 1.0, 1.75, 3.0};
  EXPECT_EQ(InterpolateAt(c, Interpolation::kZeroOrderHold, t),
            (std::vector<double>{0.0, 0.0, 10.0, 10.0, 20.0}));
  EXPECT_EQ(InterpolateAt(c, Interpolation::kLinear, t),
            (std::vector<double>{0.0, 5.0, 10.0, 17.5, 20.0}));
  // Left limits: a step that ends at a switch still sees the held value.
  EXPECT_EQ(InterpolateAt(c, Interpolation::kZeroOrderHold, {0.0, 1.0, 2.0}, true),
            (std::vector<double>{0.0, 0.0, 10.0}));
}

TEST(Interpolation, CubicIsExactForQuadraticsAndThirdOrderForSmoothSignals) {
  Channel quadratic = Sampled([](double t) { return 1.0 + 2.0 * t - 0.5 * t * t; }, 0.1, 50);
  std::vector<double> t;
  for (int k = 1; k < 480; ++k) t.push_back(0.1 + k * 0.0079);  // interior points
  std::vector<double> values = InterpolateAt(quadratic, Interpolation::kCubic, t);
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(values[i], 1.0 + 2.0 * t[i] - 0.5 * t[i] * t[i], 1e-12);
  }
  // Midpoint error of sin: O(h^3) for cubic Catmull-Rom, O(h^2) for linear.
  auto midpoint_error = [](Interpolation method, double dt) {
    Channel c = Sampled([](double t) { return std::sin(t); }, dt, static_cast<int>(4.0 / dt) + 1);
    std::vector<double> mid;
    for (size_t k = 1; k + 2 < c.t.size(); ++k) mid.push_back(c.t[k] + dt / 2);
    std::vector<double> v = InterpolateAt(c, method, mid);
    double e = 0.0;
    for (size_t i = 0; i < mid.size(); ++i) e = std::max(e, std::abs(v[i] - std::sin(mid[i])));
    return e;
  };
  EXPECT_NEAR(std::log2(midpoint_error(Interpolation::kLinear, 0.1) /
                        midpoint_error(Interpolation::kLinear, 0.05)),
              2.0, 0.2);
  EXPECT_GT(std::log2(midpoint_error(Interpolation::kCubic, 0.1) /
                      midpoint_error(Interpolation::kCubic, 0.05)),
            2.8);
}

TEST(Interpolation, NamesRoundTrip) {
  for (Interpolation i :
       {Interpolation::kZeroOrderHold, Interpolation::kLinear, Interpolation::kCubic}) {
    Interpolation back;
    ASSERT_TRUE(StringToInterpolation(InterpolationToString(i), &back));
    EXPECT_EQ(back, i);
  }
  Interpolation unused;
  EXPECT_FALSE(StringToInterpolation("spline", &unused));
}

}  // namespace trajectory_test
}  // namespace vesselid
