// A field log with the defects of real ones, through `vesselid run`: the seed 000 catamaran
// (a physical 3-DOF simulator, not the identified input-gain model) logged by a 10 Hz logger
// with +-30 ms row jitter, Unix-epoch times, GNSS latitude/longitude, heading in degrees, one
// 0/0 fix, a GNSS fix repeated while the heading turns, a fix 33 m off, a heading spike, a
// segment cut to 2 s and one to 0.9 s. The run
// must finish and name every defect in its warnings (stderr, report.txt, results.json); the
// bad-input cases of the new keys stop it with the file, line and key.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "GeographicLib/LocalCartesian.hpp"
#include "engine/data/interpolation.h"
#include "engine/data/time_base.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/input_gain/campaign.h"
#include "tests/support/bad_input_fixture.h"
#include "tests/support/run_command.h"

namespace vesselid {
namespace real_log_test {

namespace fs = std::filesystem;

struct LogOptions {
  bool defects = true;  // 0/0 fix, stale fixes, a 2-second segment
};

// Writes the log as a logger would: rows every 0.1 s +- 30 ms inside each logged segment,
// each row carrying the sensors' values at its time.
void WriteUsvLog(const fs::path& path, const LogOptions& log) {
  input_gain::CampaignOptions options;
  options.segments = 6;
  options.total_duration = 150.0;
  options.truth_columns = false;
  options.seed = 4;
  Trajectory campaign;
  std::string error;
  ASSERT_TRUE(
      input_gain::SimulateCampaign(input_gain::CatamaranParameters(), options, &campaign, &error))
      << error;
  auto channel = [&](const char* name) { return ExtractChannel(campaign, campaign.Find(name)); };
  const Channel n = channel("n"), e = channel("e"), psi = channel("heading"),
                pwm_l = channel("pwm_L"), pwm_r = channel("pwm_R"), segment = channel("segment");
  Channel psi_unwrapped = psi;
  for (size_t k = 1; k < psi.value.size(); ++k) {
    const double d = std::remainder(psi.value[k] - psi.value[k - 1], 2.0 * M_PI);
    psi_unwrapped.value[k] = psi_unwrapped.value[k - 1] + d;
  }
  // Segment spans.
  std::vector<std::pair<double, double>> spans;
  for (size_t k = 0; k < segment.t.size(); ++k) {
    if (k == 0 || segment.value[k] != segment.value[k - 1]) spans.push_back({segment.t[k], 0.0});
    spans.back().second = segment.t[k];
  }
  ASSERT_EQ(spans.size(), 6u);
  const GeographicLib::LocalCartesian plane(63.43, 10.39, 0.0);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.03, 0.03);
  std::ofstream out(path);
  out << "time,segment,lat,lon,hdg_deg,pwm_L,pwm_R\n";
  double frozen_lat = 0.0, frozen_lon = 0.0;
  for (size_t s = 0; s < spans.size(); ++s) {
    double end = spans[s].second;
    if (log.defects && s == 4) end = spans[s].first + 2.0;  // too short for least squares
    if (log.defects && s == 5) end = spans[s].first + 0.9;  // too short for any stage
    for (int j = 0;; ++j) {
      const double t = spans[s].first + 0.05 + 0.1 * j + jitter(random);
      if (t > end - 0.05) break;
      auto at = [&](const Channel& c, Interpolation how) { return InterpolateAt(c, how, {t})[0]; };
      double lat = 0.0, lon = 0.0, h = 0.0;
      plane.Reverse(at(e, Interpolation::kLinear), at(n, Interpolation::kLinear), 0.0, lat, lon, h);
      if (log.defects && s == 1 && j == 40) lat = lon = 0.0;  // no solution
      if (log.defects && s == 2 && j == 50) frozen_lat = lat, frozen_lon = lon;
      if (log.defects && s == 2 && j > 50 && j <= 56) lat = frozen_lat, lon = frozen_lon;
      if (log.defects && s == 3 && j == 30) lat += 0.0003;  // a fix 33 m north of the track
      double heading = std::fmod(at(psi_unwrapped, Interpolation::kLinear) * 180.0 / M_PI, 360.0);
      if (log.defects && s == 0 && j == 60) heading += 90.0;  // a heading spike
      if (heading < 0) heading += 360.0;
      if (heading >= 360.0) heading -= 360.0;
      char row[300];
      std::snprintf(row, sizeof(row), "%.3f,%zu,%.9f,%.9f,%.3f,%.4f,%.4f\n", 1.7e9 + 123.0 + t,
                    s + 1, lat, lon, heading, at(pwm_l, Interpolation::kZeroOrderHold),
                    at(pwm_r, Interpolation::kZeroOrderHold));
      out << row;
    }
  }
}

constexpr char kParameters[] = R"(    parameters:
      u.1: 0
      u.u: -0.5
      u.|u|u: 0
      v.v: -0.5
      v.r: 0
      r.v: 0
      r.r: -0.5
      b_u: 0.5
      b_v: 0.0
      b_r: 1.0
      k_f: 0.5
      k_r1: 1.0
      k_r2: 0.0
)";

// An output-error stage from plausible starts, then a least-squares stage (whose
// Savitzky-Golay window of 15 samples is longer than the 2-second segment); the 0.9-second
// segment has fewer samples than the model's six states for both.
std::string Config(const std::string& experiment_keys, const std::string& least_squares_keys) {
  return std::string(R"(model: {family: input_gain, type: static}
experiments:
  - name: log
    file: usv_log.csv
    time: {column: time}
    position: {lat: lat, lon: lon, origin: first}
    inputs: {u_L: pwm_L, u_R: pwm_R}
    outputs: {n: north, e: east, psi: hdg_deg}
    degrees: [hdg_deg]
    interpolation: zero_order_hold
    segments: {column: segment}
)") + experiment_keys +
         R"(stages:
  - name: output_error
    outputs: [n, e, psi]
    free_initial_states: [n, e, psi, u, v, r]
    local: {max_iterations: 10}
    parameters: {u.u: -0.5, v.v: -0.5, r.r: -0.5, b_u: 0.5, k_f: 0.5, b_r: 1.0, k_r1: 1.0}
  - name: least_squares
    type: least_squares
    outputs: [n, e, psi]
    least_squares: {grid: n, smoothing: {half_width: 7, order: 4}, robust: true)" +
         least_squares_keys + "}\n" + kParameters;
}

using RunOutcome = testing::CommandOutcome;

RunOutcome VesselidRun(const fs::path& dir) {
  return testing::RunCommand(std::string(VESSELID_BINARY) + " run " +
                             (dir / "config.yaml").string() + " --out " + (dir / "out").string());
}

class RealLog : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_real_log_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);  // kept for a look when a case fails
  }
  void WriteConfig(const std::string& text) { std::ofstream(dir_ / "config.yaml") << text; }
  fs::path dir_;
};

TEST_F(RealLog, FinishesWithEveryDefectNamed) {
  WriteUsvLog(dir_ / "usv_log.csv", {});
  WriteConfig(
      Config("    screen: {max_speed: 10, max_rate: {psi: 120}, stale: 3}\n"
             "    resample: {rate: 5}\n",
             ""));
  const RunOutcome run = VesselidRun(dir_);
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(dir_ / "out" / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  // Each record finding as a line: "experiment 'log'[, segment s]: message".
  std::string warnings;
  for (const nlohmann::json& f : results["findings"]) {
    warnings += f["kind"].get<std::string>() + " experiment '" + f["experiment"].get<std::string>() +
                "'" + (f["segment"] == "" ? "" : ", segment " + f["segment"].get<std::string>()) +
                ": " + f["message"].get<std::string>() + "\n";
  }
  std::ostringstream text;
  text << std::ifstream(dir_ / "out" / "report.txt").rdbuf();
  const std::vector<std::string> expected = {
      "experiment 'log': times are Unix epoch seconds; t = 0 is 17000001",
      "experiment 'log': removed 1 zero fix(es) (0/0) of lat/lon (t = ",
      "6 stale repeat(s) of north/east (t = ",
      "1 jump(s) faster than the screen's bound in north/east (t = ",
      "1 jump(s) faster than the screen's bound in hdg_deg (t = ",
      "experiment 'log': resampled to a uniform 5 Hz grid",
      "experiment 'log': 2 pieces of 1 record(s) skipped (log); the shortest, ",
      "s): Savitzky-Golay window of 15 samples is longer than the ",
      "experiment 'log', segment log@6: skipped (t = ",
      " sample time(s) of its outputs, fewer than the 6 the model's states need"};
  for (const std::string& e : expected) {
    EXPECT_NE(warnings.find(e), std::string::npos) << e << "\n" << warnings;
    EXPECT_NE(run.output.find(e), std::string::npos) << e;
    EXPECT_NE(text.str().find(e), std::string::npos) << e;
  }
  // Each kind as typed: the removals and skips are warnings, the origin and grid notes.
  for (const char* kind :
       {"record_origin", "samples_removed", "resampled", "segment_skipped", "record_cut"}) {
    EXPECT_NE(warnings.find(std::string(kind) + " experiment 'log'"), std::string::npos) << kind;
  }
  std::ostringstream html;
  html << std::ifstream(dir_ / "out" / "report.html").rdbuf();
  for (const char* e : {"6 stale repeat(s) of north/east", "resampled to a uniform 5 Hz grid",
                        "s): Savitzky-Golay window of 15 samples"}) {
    EXPECT_NE(html.str().find(e), std::string::npos) << e;
  }
  // The origins, exactly: the first row's time text and fix.
  std::ifstream log(dir_ / "usv_log.csv");
  std::string row;
  std::getline(log, row);
  std::getline(log, row);
  std::int64_t first = 0, origin_ns = 0;
  ASSERT_TRUE(ParseNanoseconds(row.substr(0, row.find(',')), &first));
  const nlohmann::json& origin = results["record_origins"]["log"];
  ASSERT_TRUE(ParseNanoseconds(origin["time_origin_unix"].get<std::string>(), &origin_ns));
  EXPECT_EQ(origin_ns, first);
  EXPECT_EQ(origin["time_origin_utc"].get<std::string>().substr(0, 17), "2023-11-14T22:15:");
  EXPECT_NEAR(origin["position_origin"]["lat"].get<double>(), 63.43, 1e-3);
  EXPECT_NEAR(origin["position_origin"]["lon"].get<double>(), 10.39, 1e-3);
  // Both stages ran, the short segment only left out where it is too short.
  ASSERT_EQ(results["stages"].size(), 2u);
  std::set<std::string> fitted;
  for (const auto& m : results["stages"][0]["fit"]["metrics"]) fitted.insert(m["experiment"]);
  EXPECT_EQ(fitted.size(), 5u) << results["stages"][0]["fit"].dump();
  EXPECT_EQ(fitted.count("log@5"), 1u);
  EXPECT_EQ(fitted.count("log@6"), 0u);
}

TEST_F(RealLog, RowJitterPassesTheRegressionGridWithMaxGap) {
  WriteUsvLog(dir_ / "usv_log.csv", {false});
  WriteConfig(Config("", ""));
  RunOutcome run = VesselidRun(dir_);
  EXPECT_NE(run.status, 0);
  EXPECT_TRUE(std::regex_search(
      run.output, std::regex("experiment 'log@\\d' .*step of 0\\.1[3-9]\\d* s \\(1\\.[5-9]\\d* "
                             "median steps\\) at t = .*row jitter beyond the stage's max_gap "
                             "\\(1\\.5 median steps\\); raise max_gap to 1\\.[6-9]")))
      << run.output;
  // The output-error stage before it is a result; the run says where and why it stopped.
  std::ifstream in(dir_ / "out" / "results.json");
  const nlohmann::json stopped = nlohmann::json::parse(in);
  EXPECT_EQ(stopped["stopped"]["stage"], "least_squares");
  WriteConfig(Config("", ", max_gap: 2"));
  run = VesselidRun(dir_);
  EXPECT_EQ(run.status, 0) << run.output;
}

// Bad input of the new keys: a message with the file, line and key; no results.
using testing::BadInput;

constexpr char kFixes[] =
    "t,lat,lon,psi,delta\n0,63.43,10.39,0,0\n0.1,63.4301,10.39,0,0\n0.2,95.1,10.39,0,0\n"
    "0.3,63.4303,10.39,0,0\n";

constexpr char kFixConfig[] = R"(model: {family: nomoto, type: first_order}
experiments:
  - name: run
    file: data.csv
    inputs: {delta: delta}
    outputs: {psi: psi}
    position: {lat: LAT, lon: lon}
    resample: {rate: RATE}
stages:
  - name: fit
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 50.0}
)";

std::string FixConfig(const std::string& lat, const std::string& rate) {
  std::string text = kFixConfig;
  text.replace(text.find("LAT"), 3, lat);
  text.replace(text.find("RATE"), 4, rate);
  return text;
}

TEST_F(BadInput, PositionWithoutItsLatitudeColumn) {
  std::ofstream(dir_ / "data.csv") << kFixes;
  WriteConfig(FixConfig("latitude", "5"));
  ExpectRejected(
      "experiment 'run': .*data\\.csv: no column 'latitude' "
      "\\(experiments\\[0\\]\\.position\\.lat\\)");
}

TEST_F(BadInput, LatitudeOutsideItsRange) {
  std::ofstream(dir_ / "data.csv") << kFixes;
  WriteConfig(FixConfig("lat", "5"));
  ExpectRejected(
      "data\\.csv:4: column 'lat': 95\\.1 is not a latitude \\(outside \\[-90, 90\\]\\)");
}

TEST_F(BadInput, ResampleRateNotPositive) {
  std::ofstream(dir_ / "data.csv") << kFixes;
  WriteConfig(FixConfig("lat", "0"));
  ExpectRejected("config\\.yaml:8: experiments\\[0\\]\\.resample\\.rate: must be > 0 \\(Hz\\)");
  WriteConfig(FixConfig("lat", "-2"));
  ExpectRejected("config\\.yaml:8: experiments\\[0\\]\\.resample\\.rate: must be > 0");
}

TEST_F(BadInput, OriginOutsideTheGlobe) {
  std::ofstream(dir_ / "data.csv") << kFixes;
  std::string text = FixConfig("lat", "5");
  text.replace(text.find("lon: lon}"), 9, "lon: lon, origin: [91, 10]}");
  WriteConfig(text);
  ExpectRejected(
      "config\\.yaml:7: experiments\\[0\\]\\.position\\.origin\\[0\\]: latitude must be "
      "in \\[-90, 90\\]");
}

}  // namespace real_log_test
}  // namespace vesselid
