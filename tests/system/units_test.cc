// Units end to end: a course-keeping ship that is not the model's (Norrbin, cubic yaw damping,
// a 1.5 deg rudder bias, rudder and heading noise) flies a 20/20 zigzag logged in degrees, and
// the first-order Nomoto model is identified from it. With `degrees: [psi, r, delta]` every
// trace, table and plot label says deg (deg/s for r) and shows degrees; with psi forgotten in
// `degrees:` the run warns, naming the experiment and the column, in results, report.txt and
// report.html; the correct config gets no such warning. The rudder bias follows the rudder's
// unit.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/config/config.h"
#include "engine/report/results_writer.h"
#include "engine/diagnose/run_findings.h"
#include "engine/run/display_units.h"
#include "engine/run/pipeline.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace units_test {

namespace fs = std::filesystem;

constexpr double kDeg = 180.0 / M_PI;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

constexpr char kConfig[] = R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: zz, inputs: {delta: delta}, outputs: {psi: psi, r: r}, DEGREES}
stages:
  - name: fit
    parameters:
      T: {start: 6, lower: 0.1, upper: 200}
      K: {start: 0.05, lower: 0.001, upper: 5}
      delta_0: {start: 0, lower: -0.5, upper: 0.5}
    free_initial_states: [psi, r]
)";

class UnitsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_units_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    auto ship = nomoto::MakeNorrbinHandle();
    nomoto::ClosedLoopOptions loop;
    loop.duration = 240.0;
    loop.sample_time = 0.1;
    loop.excitation.type = nomoto::Excitation::Type::kZigzag;
    loop.excitation.zigzag_rudder = 20.0 / kDeg;
    loop.excitation.zigzag_heading = 20.0 / kDeg;
    loop.rudder_noise = 0.2 / kDeg;
    loop.heading_noise = 0.1 / kDeg;
    loop.seed = 5;
    Trajectory data;
    std::string error;
    // T 8 s, K 0.08 1/s, cubic damping 20 s^2, rudder bias 1.5 deg.
    ASSERT_TRUE(
        nomoto::SimulateClosedLoop(*ship, {8.0, 0.08, 20.0, 1.5 / kDeg}, loop, &data, &error))
        << error;
    Trajectory logged;  // the logger's columns, in degrees
    logged.t = data.t;
    for (const char* name : {"delta", "psi", "r"}) {
      logged.names.push_back(name);
      logged.columns.push_back(data.columns[data.Find(name)]);
      for (double& v : logged.columns.back()) v *= kDeg;
    }
    ASSERT_TRUE(WriteTrajectoryCsv((*dir_ / "zz.csv").string(), logged, &error)) << error;
    // The same log with its time in milliseconds.
    for (double& t : logged.t) t *= 1000.0;
    ASSERT_TRUE(WriteTrajectoryCsv((*dir_ / "zz_ms.csv").string(), logged, &error)) << error;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  // Runs the config with `degrees` into <dir>/<out>; the run's result.
  static RunResult Run(const std::string& degrees, const std::string& out) {
    std::string text = kConfig;
    text.replace(text.find("DEGREES"), 7,
                 degrees + (degrees.find("file:") == std::string::npos ? ", file: zz.csv" : ""));
    std::ofstream(*dir_ / (out + ".yaml")) << text;
    RunConfig config;
    RunResult result;
    std::string error;
    if (!LoadRunConfig((*dir_ / (out + ".yaml")).string(), "", DefaultRegistry(), &config,
                       &error)) {
      ADD_FAILURE() << error;
      return result;
    }
    Identify(config, &result, &error);
    EXPECT_FALSE(result.stages.empty()) << error;
    fs::create_directories(*dir_ / out);
    EXPECT_TRUE(WriteRunResults(config, result, (*dir_ / out).string(), &error)) << error;
    return result;
  }

  // The unit_suspect findings' outputs (columns) of a run.
  static std::vector<std::string> SuspectUnits(const RunResult& result) {
    std::vector<std::string> columns;
    for (const Finding& f : result.findings) {
      if (f.kind != FindingKind::kUnitSuspect) continue;
      columns.push_back(!f.output.empty() ? f.output : !f.input.empty() ? f.input : "time");
    }
    return columns;
  }

  static bool WarnsOfDegrees(const RunResult& result) {
    for (const Finding& f : result.findings) {
      if (f.kind == FindingKind::kUnitSuspect && f.experiment == "zz" && f.output == "psi" &&
          f.message.rfind("column 'psi' looks like degrees", 0) == 0) {
        return true;
      }
    }
    return false;
  }

  static fs::path* dir_;
};

fs::path* UnitsTest::dir_ = nullptr;

TEST_F(UnitsTest, DegreesAreShownInDegrees) {
  const RunResult result = Run("degrees: [psi, r, delta]", "deg");
  EXPECT_FALSE(WarnsOfDegrees(result));
  ASSERT_FALSE(result.stages.empty());
  // The trace in the data's unit, the unit in its header.
  const fs::path trace = *dir_ / "deg" / "traces" / "fit.zz.csv";
  Trajectory shown, logged;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv(trace.string(), {}, &shown, &error)) << error;
  ASSERT_TRUE(ReadTrajectoryCsv((*dir_ / "zz.csv").string(), {}, &logged, &error)) << error;
  const int psi = shown.Find("psi_measured [deg]"), r = shown.Find("r_simulated [deg/s]");
  ASSERT_GE(psi, 0) << ReadText(trace).substr(0, 200);
  ASSERT_GE(r, 0) << ReadText(trace).substr(0, 200);
  const std::vector<double>& logged_psi = logged.columns[logged.Find("psi")];
  double largest = 0.0, logged_largest = 0.0;
  for (double v : shown.columns[psi])
    largest = std::max(largest, std::isnan(v) ? 0.0 : std::abs(v));
  for (double v : logged_psi) logged_largest = std::max(logged_largest, std::abs(v));
  EXPECT_NEAR(largest, logged_largest, 1e-6 * logged_largest);
  EXPECT_GT(largest, 20.0);  // degrees, not radians
  // report.txt and results.json: RMSE in degrees, named.
  const std::string text = ReadText(*dir_ / "deg" / "report.txt");
  EXPECT_NE(text.find("RMSE psi [deg]"), std::string::npos) << text;
  EXPECT_NE(text.find("RMSE r [deg/s]"), std::string::npos) << text;
  const nlohmann::json results = nlohmann::json::parse(ReadText(*dir_ / "deg" / "results.json"));
  const nlohmann::json& metrics = results.at("stages")[0].at("fit").at("metrics");
  bool psi_in_degrees = false;
  for (const nlohmann::json& m : metrics) {
    if (m.at("output") != "psi") continue;
    psi_in_degrees = m.at("unit") == "deg";
    // The fit is within a degree or two; in radians that RMSE would be below 0.05.
    const double rmse = m.at("rmse").get<double>();
    EXPECT_GT(rmse, 0.05);
    EXPECT_NEAR(rmse, result.stages[0].summary.fits[0].channels[0].rmse * kDeg, 1e-9 * rmse);
  }
  EXPECT_TRUE(psi_in_degrees);
  const std::string html = ReadText(*dir_ / "deg" / "report.html");
  EXPECT_NE(html.find("<th>RMSE psi [deg]</th>"), std::string::npos);
  EXPECT_NE(html.find("<td>deg/s</td>"), std::string::npos);
}

// The rudder bias is an angle of the rudder: shown in degrees where the rudder column is read
// in degrees (value, standard error, interval and bounds alike), kept in radians in
// results.json with both units stated; in radians where the rudder column is.
TEST_F(UnitsTest, RudderBiasIsShownInTheRuddersUnit) {
  const RunResult result = Run("degrees: [psi, r, delta]", "bias");
  ASSERT_FALSE(result.parameters.empty());
  double bias = NAN;  // [rad]
  for (const FinalParameter& f : result.parameters) {
    if (f.name == "delta_0") bias = f.value;
  }
  // Truth 1.5 deg; the first-order model (no cubic damping) gets it within a degree.
  EXPECT_NEAR(bias * kDeg, 1.5, 1.0);
  const std::string text = ReadText(*dir_ / "bias" / "report.txt");
  const size_t row = text.find("\n  delta_0 ");
  ASSERT_NE(row, std::string::npos) << text;
  const std::string line = text.substr(row + 1, text.find('\n', row + 1) - row - 1);
  char shown[32];
  std::snprintf(shown, sizeof(shown), "%.8g", bias * kDeg);
  EXPECT_NE(line.find(shown), std::string::npos) << line;
  EXPECT_NE(line.find(" deg "), std::string::npos) << line;
  const std::string html = ReadText(*dir_ / "bias" / "report.html");
  // Bounds +-0.5 rad as configured, shown in degrees.
  EXPECT_NE(html.find("[-28.6479, 28.6479]"), std::string::npos);
  const nlohmann::json results = nlohmann::json::parse(ReadText(*dir_ / "bias" / "results.json"));
  bool stated = false;
  for (const nlohmann::json& p : results.at("parameters")) {
    if (p.at("name") != "delta_0") continue;
    stated = true;
    EXPECT_DOUBLE_EQ(p.at("value").get<double>(), bias);
    EXPECT_EQ(p.at("unit"), "rad");
    EXPECT_EQ(p.at("shown_unit"), "deg");
    EXPECT_DOUBLE_EQ(p.at("shown_scale").get<double>(), kDeg);
    EXPECT_EQ(p.at("bounds"), nlohmann::json::parse("[-0.5, 0.5]"));
  }
  EXPECT_TRUE(stated);
  // Where the rudder is read in radians the bias is shown in radians; T keeps its seconds.
  std::string config_text = kConfig;
  config_text.replace(config_text.find("DEGREES"), 7, "degrees: [psi, r], file: zz.csv");
  std::ofstream(*dir_ / "radian_rudder.yaml") << config_text;
  RunConfig config;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((*dir_ / "radian_rudder.yaml").string(), "", DefaultRegistry(),
                            &config, &error))
      << error;
  EXPECT_EQ(ParameterDisplayUnit(config, "delta_0").unit, "rad");
  EXPECT_EQ(ParameterDisplayUnit(config, "delta_0").scale, 1.0);
  EXPECT_EQ(ParameterDisplayUnit(config, "T").unit, "s");
  EXPECT_EQ(ParameterDisplayUnit(config, "x0.psi[zz]").unit, "deg");
}

TEST_F(UnitsTest, HeadingInDegreesReadAsRadiansIsNamed) {
  const RunResult wrong = Run("degrees: [r, delta]", "rad");
  EXPECT_TRUE(WarnsOfDegrees(wrong));
  for (const char* file : {"report.txt", "report.html", "results.json"}) {
    const std::string text = ReadText(*dir_ / "rad" / file);
    const bool named = text.find("column 'psi' looks like degrees") != std::string::npos ||
                       text.find("column &#39;psi&#39; looks like degrees") != std::string::npos;
    EXPECT_TRUE(named) << file;
  }
  // Compared modulo one turn, the wrapped residual stays below pi; the fit must not hide it.
  const RunResult wrapped = Run("degrees: [r, delta], wrap: [psi]", "wrapped");
  EXPECT_TRUE(WarnsOfDegrees(wrapped));
  ASSERT_FALSE(wrapped.stages.empty());
  for (const ChannelMetrics& m : wrapped.stages[0].summary.fits[0].channels) {
    if (m.output == "psi") {
      EXPECT_LT(m.fit_percent, 50.0);
    }
  }
}

}  // namespace units_test
}  // namespace vesselid

namespace vesselid {
namespace units_test {

// A rudder logged in degrees but not listed: the input check names it (10-20 "rad" is beyond
// any rudder), with the value; the heading listed correctly stays quiet. Listed, nothing.
TEST_F(UnitsTest, RudderInDegreesReadAsRadiansIsNamed) {
  const RunResult forgotten = Run("degrees: [psi, r]", "nodelta");
  EXPECT_EQ(SuspectUnits(forgotten), std::vector<std::string>{"delta"});
  for (const Finding& f : forgotten.findings) {
    if (f.kind != FindingKind::kUnitSuspect) continue;
    EXPECT_EQ(f.experiment, "zz");
    EXPECT_GT(f.value, 20.0);
    EXPECT_NE(f.message.find("input column 'delta' reaches"), std::string::npos) << f.message;
  }
  EXPECT_TRUE(SuspectUnits(Run("degrees: [psi, r, delta]", "alldeg")).empty());
}

// Time logged in milliseconds and read as seconds: a median sample interval of 100 s is named;
// with `time: {unit: ms}` the run is quiet and identifies what the seconds log does.
TEST_F(UnitsTest, TimeInMillisecondsIsNamedAndReadWithItsUnit) {
  // Read as seconds the record's steps of 100 "s" make the simulation diverge: the refusal says
  // what the time column looks like and how to read it.
  std::string text = kConfig;
  text.replace(text.find("DEGREES"), 7, "degrees: [psi, r, delta], file: zz_ms.csv");
  std::ofstream(*dir_ / "ms.yaml") << text;
  RunConfig config;
  RunResult ms;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((*dir_ / "ms.yaml").string(), "", DefaultRegistry(), &config, &error))
      << error;
  if (Identify(config, &ms, &error)) {
    EXPECT_EQ(SuspectUnits(ms), std::vector<std::string>{"time"});
  } else {
    EXPECT_NE(error.find("median sample interval is 100 s"), std::string::npos) << error;
    EXPECT_NE(error.find("time: {unit: ms}"), std::string::npos) << error;
  }
  const RunResult read = Run("degrees: [psi, r, delta], file: zz_ms.csv, time: {unit: ms}", "msread");
  EXPECT_TRUE(SuspectUnits(read).empty());
  // A log in seconds read as milliseconds: a median interval of 0.1 ms, named too.
  const RunResult too_fine = Run("degrees: [psi, r, delta], time: {unit: ms}", "sasms");
  EXPECT_EQ(SuspectUnits(too_fine), std::vector<std::string>{"time"});
  const RunResult seconds = Run("degrees: [psi, r, delta]", "seconds");
  ASSERT_FALSE(read.parameters.empty());
  ASSERT_EQ(read.parameters.size(), seconds.parameters.size());
  for (size_t i = 0; i < read.parameters.size(); ++i) {
    EXPECT_NEAR(read.parameters[i].value, seconds.parameters[i].value,
                1e-6 * std::abs(seconds.parameters[i].value) + 1e-12)
        << read.parameters[i].name;
  }
}

}  // namespace units_test
}  // namespace vesselid
