// The identified model of a run built in memory (IdentifiedModelOf(config, result)) is the
// one its results.json gives (ReadIdentifiedModel): the same values, standard errors,
// covariance, ensemble, step and interpolation, to the bit. Shipped configs run in process
// on their simulated data, one with a bootstrap covariance (the ensemble is its replicates).
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/export/run_folder_model.h"
#include "engine/output/identified_model.h"
#include "engine/output/run_document.h"
#include "engine/report/results_writer.h"
#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace identified_model_test {

namespace fs = std::filesystem;

// Equal to the bit, NaN equal to NaN.
bool Same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b); }

void ExpectSame(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(Same(a[i], b[i])) << what << "[" << i << "]";
}

void ExpectSameDocument(const RunDocument& a, const RunDocument& b) {
  EXPECT_EQ(a.family, b.family);
  EXPECT_EQ(a.options, b.options);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(a.parameters[i].name, b.parameters[i].name);
    EXPECT_EQ(a.parameters[i].role, b.parameters[i].role);
    EXPECT_TRUE(Same(a.parameters[i].value, b.parameters[i].value)) << a.parameters[i].name;
    EXPECT_TRUE(Same(a.parameters[i].std_error, b.parameters[i].std_error)) << a.parameters[i].name;
  }
  EXPECT_EQ(a.correlation_names, b.correlation_names);
  ASSERT_EQ(a.correlation.size(), b.correlation.size());
  for (int i = 0; i < a.correlation.size(); ++i) {
    EXPECT_TRUE(Same(a.correlation.data()[i], b.correlation.data()[i]));
  }
  EXPECT_EQ(a.replicate_names, b.replicate_names);
  ASSERT_EQ(a.replicate_values.size(), b.replicate_values.size());
  for (size_t r = 0; r < a.replicate_values.size(); ++r) {
    ExpectSame(a.replicate_values[r], b.replicate_values[r], "replicate");
  }
  EXPECT_EQ(a.has_model_stage, b.has_model_stage);
  EXPECT_TRUE(Same(a.integration_step, b.integration_step));
  EXPECT_TRUE(Same(a.max_step, b.max_step));
  EXPECT_EQ(a.interpolation, b.interpolation);
  ASSERT_EQ(a.fit_metrics.size(), b.fit_metrics.size());
  for (size_t i = 0; i < a.fit_metrics.size(); ++i) {
    EXPECT_EQ(a.fit_metrics[i].output, b.fit_metrics[i].output);
    EXPECT_EQ(a.fit_metrics[i].unit, b.fit_metrics[i].unit);
    EXPECT_TRUE(Same(a.fit_metrics[i].rmse, b.fit_metrics[i].rmse));
    EXPECT_TRUE(Same(a.fit_metrics[i].samples, b.fit_metrics[i].samples));
  }
  EXPECT_EQ(a.free_initial_states, b.free_initial_states);
  ASSERT_EQ(a.zigzags.size(), b.zigzags.size());
  for (size_t i = 0; i < a.zigzags.size(); ++i) {
    EXPECT_EQ(a.zigzags[i].experiment, b.zigzags[i].experiment);
    EXPECT_TRUE(Same(a.zigzags[i].simulated_first, b.zigzags[i].simulated_first));
    EXPECT_TRUE(Same(a.zigzags[i].measured_second, b.zigzags[i].measured_second));
  }
}

// Runs configs/<name>.yaml on its simulated data (the last stage's covariance by a block
// bootstrap of `bootstrap_runs` replicates when > 0), writes its outputs and compares the
// model made in memory with the model read back.
void CompareInMemoryAndRead(const std::string& name, int bootstrap_runs) {
  const ModelRegistry registry = DefaultRegistry();
  const std::string path = std::string(VESSELID_SOURCE_DIR) + "/configs/" + name + ".yaml";
  const fs::path out =
      fs::temp_directory_path() / ("vesselid_identified_model_" + name + std::to_string(::getpid()));
  fs::remove_all(out);
  ConfigFile file;
  std::string error;
  ASSERT_TRUE(LoadConfigFile(path, out.string(), registry, &file, &error, false)) << error;
  ASSERT_TRUE(SimulateConfig(file, out.string(), &error)) << error;
  ASSERT_TRUE(LoadConfigFile(path, out.string(), registry, &file, &error)) << error;
  if (bootstrap_runs > 0) {
    UncertaintyOptions& u = file.run.stages.back().options.uncertainty;
    u.method = UncertaintyMethod::kBlockBootstrap;
    u.bootstrap.runs = bootstrap_runs;
  }
  RunResult result;
  ASSERT_TRUE(Identify(file.run, &result, &error)) << error;
  ASSERT_TRUE(WriteRunResults(file.run, result, out.string(), &error, false)) << error;

  RunDocument read;
  ASSERT_TRUE(ReadRunDocument(out.string(), &read, &error)) << error;
  ExpectSameDocument(RunDocumentOf(file.run, result), read);
  if (bootstrap_runs > 0) {
    EXPECT_FALSE(read.replicate_values.empty());
  }

  IdentifiedModel in_memory, from_file;
  ASSERT_TRUE(IdentifiedModelOf(file.run, result, 20, 7, &in_memory, &error)) << error;
  ASSERT_TRUE(ReadIdentifiedModel(out.string(), registry, 20, 7, &from_file, &error)) << error;
  EXPECT_EQ(in_memory.model, from_file.model);
  EXPECT_EQ(in_memory.ensemble_source, bootstrap_runs > 0 ? "bootstrap" : "covariance");
  EXPECT_EQ(in_memory.ensemble_source, from_file.ensemble_source);
  ExpectSame(in_memory.values, from_file.values, "values");
  ExpectSame(in_memory.std_errors, from_file.std_errors, "std_errors");
  EXPECT_EQ(in_memory.covariance_names, from_file.covariance_names);
  ASSERT_EQ(in_memory.covariance.size(), from_file.covariance.size());
  for (int i = 0; i < in_memory.covariance.size(); ++i) {
    EXPECT_TRUE(Same(in_memory.covariance.data()[i], from_file.covariance.data()[i]));
  }
  ASSERT_EQ(in_memory.ensemble.size(), from_file.ensemble.size());
  for (size_t m = 0; m < in_memory.ensemble.size(); ++m) {
    ExpectSame(in_memory.ensemble[m], from_file.ensemble[m], "member");
  }
  EXPECT_TRUE(Same(in_memory.max_step, from_file.max_step));
  EXPECT_EQ(in_memory.interpolation, from_file.interpolation);
  ASSERT_NE(in_memory.handle, nullptr);
  EXPECT_EQ(in_memory.handle->info().name, in_memory.model);
  fs::remove_all(out);
}

TEST(IdentifiedModel, InMemoryIsWhatResultsJsonGives) {
  CompareInMemoryAndRead("nomoto_cargo", 0);
}

TEST(IdentifiedModel, InMemoryBootstrapEnsembleIsWhatResultsJsonGives) {
  CompareInMemoryAndRead("nomoto_patrol", 12);
}

// The run's data in degrees: the model says which of its channels they are.
TEST(IdentifiedModel, NamesTheChannelsTheDataGaveInDegrees) {
  const ModelRegistry registry = DefaultRegistry();
  ConfigFile file;
  std::string error;
  const std::string path = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
  ASSERT_TRUE(LoadConfigFile(path, "", registry, &file, &error, false)) << error;
  RunResult empty;
  IdentifiedModel model;
  ASSERT_TRUE(IdentifiedModelOf(file.run, empty, 0, 1, &model, &error)) << error;
  EXPECT_EQ(model.degree_names, (std::vector<std::string>{"delta", "psi"}));
}

}  // namespace identified_model_test
}  // namespace vesselid
