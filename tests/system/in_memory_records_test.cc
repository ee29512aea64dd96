// Records handed over in memory (ExperimentSpec::table, trajectory_table.h), configs given
// as text (ConfigSource) and models made from plain options (ModelRegistry::MakeModel): the
// same run as from the files, and bad tables refused by row and column.
//
// The run: the shipped tanker campaign (configs/nomoto_tanker.yaml, simulated by `vesselid
// simulate`: a Norrbin ship with a rate-limited steering gear, a slow yaw disturbance and a
// quantised compass, logged in degrees) cut to three training runs and one held-out run. Its
// files are read whole into tables (every column, as a notebook's DataFrame would hold them),
// the config is given as text without `file` keys, and results.json must equal the run from
// the files bit for bit, timings and the config's name apart.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "engine/config/config.h"
#include "engine/data/trajectory_table.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/results_json.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "tests/support/results_json_times.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace in_memory_records_test {

using nlohmann::json;
using testing::DropTimes;
namespace fs = std::filesystem;

class InMemoryRecords : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_in_memory_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const std::string shipped = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " + shipped + " --out " +
                                 dir_->string() + " > /dev/null";
    simulated_ = std::system(simulate.c_str()) == 0;
    YAML::Node config = YAML::LoadFile(shipped);
    config.remove("simulation");
    config["sets"]["training"] = std::vector<std::string>{"zz10s_a", "zz20s_a", "zz35p_a"};
    config["sets"]["held_out"] = std::vector<std::string>{"zz20s_b"};
    std::ofstream(*dir_ / "config.yaml") << YAML::Dump(config) << "\n";
    // The same without the files: the notebook's config.
    YAML::Node experiments = config["experiments"];
    for (size_t i = 0; i < experiments.size(); ++i) experiments[i].remove("file");
    std::ostringstream text;
    text << config;
    text_ = new std::string(text.str());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete text_;
  }

  static fs::path* dir_;
  static std::string* text_;
  static bool simulated_;
};

fs::path* InMemoryRecords::dir_ = nullptr;
std::string* InMemoryRecords::text_ = nullptr;
bool InMemoryRecords::simulated_ = false;

json RunToJson(const ConfigFile& config) {
  RunResult result;
  std::string error;
  EXPECT_TRUE(Identify(config.run, &result, &error)) << error;
  json j = RunResultToJson(config.run, result);
  DropTimes(&j);
  j.erase("config");
  return j;
}

TEST_F(InMemoryRecords, TablesAndTextGiveTheRunOfTheFiles) {
  ASSERT_TRUE(simulated_);
  const ModelRegistry registry = DefaultRegistry();
  ConfigFile from_files;
  std::string error;
  ASSERT_TRUE(LoadConfigFile((*dir_ / "config.yaml").string(), dir_->string(), registry,
                             &from_files, &error))
      << error;

  ConfigSource source;
  source.path = "notebook";
  source.text = *text_;
  for (const ExperimentSpec& spec : from_files.run.experiments) source.in_memory.insert(spec.name);
  ConfigFile in_memory;
  ASSERT_TRUE(LoadConfig(source, registry, &in_memory, &error)) << error;
  for (ExperimentSpec& spec : in_memory.run.experiments) {
    EXPECT_TRUE(spec.file.empty());
    auto table = std::make_shared<Trajectory>();
    ASSERT_TRUE(ReadTrajectoryCsv((*dir_ / (spec.name + ".csv")).string(), table.get(), &error))
        << error;
    table->names.insert(table->names.begin(), "t");
    table->columns.insert(table->columns.begin(), table->t);
    table->t.clear();
    table->line.clear();
    table->source = "experiment '" + spec.name + "' (in memory)";
    spec.table = table;
  }
  const json files = RunToJson(from_files), tables = RunToJson(in_memory);
  ASSERT_FALSE(files["stages"].empty());
  EXPECT_TRUE(files == tables) << files.dump().substr(0, 600) << "\n"
                               << tables.dump().substr(0, 600);
}

TEST_F(InMemoryRecords, AnExperimentWithoutFileOrDataIsRefusedWithItsLine) {
  const ModelRegistry registry = DefaultRegistry();
  ConfigSource source;
  source.path = "notebook";
  source.text = *text_;
  source.in_memory = {"zz10s_a"};  // the others have neither
  ConfigFile config;
  std::string error;
  EXPECT_FALSE(LoadConfig(source, registry, &config, &error));
  EXPECT_NE(error.find("notebook:"), std::string::npos) << error;
  EXPECT_NE(error.find("missing key 'file' (or 'files', a pattern), and no data given for it"),
            std::string::npos)
      << error;
}

// A model from its family's name and plain options, no YAML in the caller's hands.
TEST(ModelFromOptions, BuildsTheFamilysModelOrSaysWhatIsWrong) {
  const ModelRegistry registry = DefaultRegistry();
  std::string error;
  const auto second = registry.MakeModel("nomoto", {{"type", "second_order"}}, &error);
  ASSERT_NE(second, nullptr) << error;
  EXPECT_EQ(second->info().name, "nomoto_second_order");
  EXPECT_EQ(second->info().parameters,
            (std::vector<std::string>{"T1", "T2", "T3", "K", "delta_0"}));
  EXPECT_EQ(registry.MakeModel("nomotto", {}, &error), nullptr);
  EXPECT_NE(error.find("unknown model family 'nomotto' ("), std::string::npos) << error;
  EXPECT_EQ(registry.MakeModel("nomoto", {{"type", "third_order"}}, &error), nullptr);
  EXPECT_NE(error.find("model.type"), std::string::npos) << error;
  EXPECT_NE(error.find("third_order"), std::string::npos) << error;
}

// A table of t, a, b with `edit` applied; the message TrajectoryFromTable gives, "" if none.
template <class Edit>
std::string Refusal(Edit edit, CsvReadOptions options = CsvReadOptions()) {
  Trajectory table;
  table.source = "experiment 'x' (in memory)";
  table.names = {"t", "a", "b"};
  table.columns = {{0.0, 0.1, 0.2, 0.3}, {1.0, 2.0, NAN, 4.0}, {5.0, 6.0, 7.0, 8.0}};
  edit(&table);
  Trajectory out;
  std::string error;
  return TrajectoryFromTable(table, options, &out, &error) ? "" : error;
}

TEST(TrajectoryFromTable, KeepsTheMappedColumnsAndListsTheOthers) {
  Trajectory table;
  table.names = {"a", "t", "b"};
  table.columns = {{1.0, NAN}, {0.0, 0.5}, {3.0, 4.0}};
  CsvReadOptions options;
  options.columns = {"a"};
  Trajectory out;
  std::string error;
  ASSERT_TRUE(TrajectoryFromTable(table, options, &out, &error)) << error;
  EXPECT_EQ(out.t, (std::vector<double>{0.0, 0.5}));
  ASSERT_EQ(out.names, std::vector<std::string>{"a"});
  EXPECT_EQ(out.columns[0][0], 1.0);
  EXPECT_TRUE(std::isnan(out.columns[0][1])) << "NaN is a missing sample";
  EXPECT_EQ(out.skipped_columns, std::vector<std::string>{"b"});
  EXPECT_FALSE(out.epoch);
}

TEST(TrajectoryFromTable, EpochTimesBecomeRelative) {
  Trajectory table;
  table.names = {"t", "a"};
  table.columns = {{1.7e9, 1.7e9 + 0.5}, {1.0, 2.0}};
  Trajectory out;
  std::string error;
  ASSERT_TRUE(TrajectoryFromTable(table, CsvReadOptions(), &out, &error)) << error;
  EXPECT_TRUE(out.epoch);
  EXPECT_EQ(out.time_origin_ns, 1700000000000000000LL);
  EXPECT_EQ(out.t, (std::vector<double>{0.0, 0.5}));
}

TEST(TrajectoryFromTable, BadTablesAreRefusedByRowAndColumn) {
  EXPECT_EQ(Refusal([](Trajectory*) {}), "");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->names[0] = "time"; }),
            "experiment 'x' (in memory): no time column 't'");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->columns[0][2] = 0.1; }),
            "experiment 'x' (in memory): row 2: time 0.10000000000000001 does not increase "
            "(previous 0.10000000000000001)");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->columns[0][1] = NAN; }),
            "experiment 'x' (in memory): row 1: the time is not a finite number");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->columns[2][3] = INFINITY; }),
            "experiment 'x' (in memory): column 'b', row 3: inf is not a measurement (a missing "
            "sample is NaN)");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->columns[1].pop_back(); }),
            "experiment 'x' (in memory): column 'a' has 3 rows, the time 4");
  EXPECT_EQ(Refusal([](Trajectory* t) { t->names[2] = "a"; }),
            "experiment 'x' (in memory): duplicate column 'a'");
  EXPECT_EQ(Refusal([](Trajectory* t) {
              for (auto& c : t->columns) c.resize(1);
            }),
            "experiment 'x' (in memory): fewer than two rows");
  CsvReadOptions small;
  small.max_values = 10;
  EXPECT_EQ(Refusal([](Trajectory*) {}, small),
            "experiment 'x' (in memory): 4 rows x 3 columns is more than limits.data_values (10)");
}

}  // namespace in_memory_records_test
}  // namespace vesselid
