// A log as a spreadsheet exports it, through `vesselid simulate` and `vesselid run`: two
// zigzags of a Norrbin ship with a rate-limited steering gear, a slow yaw disturbance and a
// compass in whole degrees (none of which the identified model has), rewritten with an unnamed
// index column first, a text timestamp column and a text comment column no experiment maps,
// 1 % of the rudder cells mangled ("jan.68"), and two gaps. A least-squares stage (one record
// resampled to 1 Hz, one as logged) then output error. The run must finish with every defect a
// finding and the estimates near the truth; above the bad_cells share the file is refused.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/findings.h"
#include "tests/support/run_command.h"

namespace vesselid {
namespace log_as_logged_test {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr char kSimulation[] = R"(model: {family: nomoto, type: norrbin}
simulation:
  truth: {T: 60.0, K: 0.05, alpha: 1000.0, delta_0: 0.0}
  steering_gear: {Tm: 1.0, rudder_limit_deg: 35, rate_limit_deg_s: 2.3}
  sample_time: 1.0
  degrees: true
  experiments:
    - {file: zz1.csv, duration: 900, rudder_bias_deg: 1.0,
       excitation: {type: zigzag, rudder_deg: 20, heading_deg: 10, first: starboard},
       disturbance: {rudder_deg: 0.4, period: 420}, seed: 1,
       noise: {rudder_deg: 0.1, heading_deg: 0.05, heading_resolution_deg: 1.0}}
    - {file: zz2.csv, duration: 900, rudder_bias_deg: 1.0,
       excitation: {type: zigzag, rudder_deg: 20, heading_deg: 10, first: port},
       disturbance: {rudder_deg: 0.4, period: 500}, seed: 2,
       noise: {rudder_deg: 0.1, heading_deg: 0.05, heading_resolution_deg: 1.0}}
experiments:
  - {name: zz1, file: zz1.csv, inputs: {delta: delta}, outputs: {psi: psi}, degrees: [delta, psi]}
stages:
  - name: fit
    parameters:
      T: {start: 40, lower: 1, upper: 500}
)";

constexpr char kRun[] = R"(model: {family: nomoto, type: norrbin}
experiments:
  - {name: zz1, file: zz1_log.csv, inputs: {delta: delta}, outputs: {psi: psi},
     degrees: [delta, psi]BAD_CELLS}
  - {name: zz2, file: zz2_log.csv, inputs: {delta: delta}, outputs: {psi: psi},
     degrees: [delta, psi], resample: {rate: 1}}
stages:
  - name: least_squares
    type: least_squares
    parameters: &parameters
      T: {start: 40, lower: 1, upper: 500}
      K: {start: 0.03, lower: 0.001, upper: 1}
      alpha: {start: 0, lower: 0, upper: 1e5}
      delta_0: {start: 0, lower: -0.1, upper: 0.1}
  - name: output_error
    parameters: *parameters
    free_initial_states: [psi, r]
)";

// Rewrites the simulator's `name`.csv as `name`_log.csv: an unnamed index column, t, a text
// timestamp, delta (every `mangle_every`-th cell from row 50 "jan.68"), psi, r, a text comment;
// rows of 300-309 s and 600-604 s left out.
void WriteLoggedCopy(const fs::path& dir, const std::string& name, int mangle_every) {
  Trajectory data;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv((dir / (name + ".csv")).string(), &data, &error)) << error;
  const int delta = data.Find("delta"), psi = data.Find("psi"), r = data.Find("r");
  ASSERT_GE(delta, 0);
  std::ofstream out(dir / (name + "_log.csv"));
  out << ",t,stamp,delta,psi,r,comment\n";
  for (size_t k = 0; k < data.t.size(); ++k) {
    const double t = data.t[k];
    if ((t >= 300 && t < 310) || (t >= 600 && t < 605)) continue;
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "2026-05-01 10:%02d:%02d", static_cast<int>(t) / 60 % 60,
                  static_cast<int>(t) % 60);
    std::ostringstream row;
    row.precision(12);
    row << k << ',' << t << ',' << stamp << ',';
    if (k >= 50 && (k - 50) % mangle_every == 0) {
      row << "jan.68";
    } else {
      row << data.columns[delta][k];
    }
    row << ',' << data.columns[psi][k] << ',' << data.columns[r][k] << ','
        << (k % 50 == 0 ? "12.jan" : "ok") << '\n';
    out << row.str();
  }
}

class LogAsLogged : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_log_as_logged_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "simulation.yaml") << kSimulation;
    const testing::CommandOutcome simulated =
        testing::RunCommand(std::string(VESSELID_BINARY) + " simulate " +
                            (dir_ / "simulation.yaml").string() + " --out " + dir_.string());
    ASSERT_EQ(simulated.status, 0) << simulated.output;
  }
  void TearDown() override { fs::remove_all(dir_); }

  testing::CommandOutcome Run(const std::string& bad_cells) {
    std::string config = kRun;
    config.replace(config.find("BAD_CELLS"), 9, bad_cells);
    std::ofstream(dir_ / "run.yaml") << config;
    return testing::RunCommand(std::string(VESSELID_BINARY) + " run " +
                               (dir_ / "run.yaml").string() + " --out " +
                               (dir_ / "out").string());
  }

  fs::path dir_;
};

TEST_F(LogAsLogged, RunsToTheEndWithEveryDefectAFinding) {
  WriteLoggedCopy(dir_, "zz1", 100);  // 9 of 886 rudder cells: 1 %
  WriteLoggedCopy(dir_, "zz2", 100);
  const testing::CommandOutcome run = Run("");
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(dir_ / "out" / "results.json");
  const json results = json::parse(in);
  // The mangled rudder cells: one finding per record, with the count, the column and the
  // first lines.
  for (const std::string experiment : {"zz1", "zz2"}) {
    const json bad = testing::JsonFindingFor(results, "bad_cells", experiment);
    ASSERT_FALSE(bad.is_null()) << experiment << "\n" << testing::JsonFindingsText(results);
    EXPECT_EQ(bad["output"], "delta");
    EXPECT_EQ(bad["value"], 9);
    EXPECT_NE(bad["message"].get<std::string>().find("'jan.68'"), std::string::npos);
    EXPECT_NE(bad["message"].get<std::string>().find("t = 50 s (line 52), 150 s (line 152)"), std::string::npos)
        << bad["message"];
    // The unmapped columns are named, the unnamed one too.
    const json skipped = testing::JsonFindingFor(results, "columns_not_read", experiment);
    ASSERT_FALSE(skipped.is_null()) << experiment;
    EXPECT_EQ(skipped["value"], 4);  // (unnamed), stamp, r, comment
    EXPECT_NE(skipped["message"].get<std::string>().find("(unnamed), 'stamp'"), std::string::npos)
        << skipped["message"];
    // The compass in whole degrees, in the unit it was logged in.
    const json quantised = testing::JsonFindingFor(results, "quantised", experiment);
    ASSERT_FALSE(quantised.is_null()) << experiment;
    EXPECT_EQ(quantised["output"], "psi");
    EXPECT_NEAR(quantised["value"].get<double>(), 1.0, 1e-9);
    // The gaps, with the longer one's length.
    const json gaps = testing::JsonFindingFor(results, "gaps", experiment);
    ASSERT_FALSE(gaps.is_null()) << experiment;
    EXPECT_NEAR(gaps["value"].get<double>(), 11.0, 1e-9);
  }
  // The least-squares stage cuts both records at the gaps, the resampled one too (one gap
  // rule: a resampled record is cut or accepted, never refused).
  // (one finding for both, naming them)
  const std::vector<json> cut = testing::JsonFindingsOf(results, "record_cut", "2 records cut into");
  ASSERT_EQ(cut.size(), 1u) << testing::JsonFindingsText(results);
  EXPECT_NE(cut[0]["message"].get<std::string>().find("(zz1, zz2)"), std::string::npos)
      << cut[0]["message"];
  EXPECT_FALSE(testing::JsonFindingFor(results, "resampled", "zz2").is_null());
  // Nothing failed, and the estimates are those of a good fit: K/T (what zigzags of a stable
  // ship determine) within 10 % of the truth's 0.05/60 despite the unmodelled gear and
  // disturbance, and a heading fit above 90 %.
  EXPECT_NE(results["verdict"], "failed");
  std::map<std::string, double> value;
  for (const json& p : results["parameters"]) value[p["name"]] = p["value"].get<double>();
  EXPECT_NEAR(value["K"] / value["T"], 0.05 / 60.0, 0.1 * 0.05 / 60.0) << results["parameters"];
  for (const auto& stage : results["stages"]) {
    if (stage["name"] != "output_error") continue;
    for (const json& m : stage["fit"]["metrics"]) {
      EXPECT_GT(m["fit_percent"].get<double>(), 90.0) << m.dump();
    }
  }
}

TEST_F(LogAsLogged, MangledCellsAboveTheShareRefuseTheFileNamingTheFirst) {
  WriteLoggedCopy(dir_, "zz1", 10);  // 10 %
  WriteLoggedCopy(dir_, "zz2", 100);
  testing::CommandOutcome run = Run("");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("zz1_log.csv:52: column 'delta': 'jan.68' is not a finite number (84 "
                            "of the column's 886 cells are not numbers, more than the 5 % an "
                            "experiment's bad_cells accepts)"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "results.json"));
  // A larger share accepted by the key.
  run = Run(", bad_cells: 0.2");
  EXPECT_EQ(run.status, 0) << run.output;
}

}  // namespace log_as_logged_test
}  // namespace vesselid
