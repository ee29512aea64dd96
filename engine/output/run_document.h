// What a finished run's results.json says that the commands reading the run use (export,
// predict, design, a reference model), read by one reader beside the writer (results_json.h):
// nothing else reads results.json by key.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "Eigen/Core"
#include "engine/output/held_out_zigzags.h"
#include "engine/output/process_noise.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

struct RunDocument {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string path;  // the results.json read
  std::string family;
  ModelOptions options;  // the final model's: the last model stage's, else the run's
  struct Parameter {
    std::string name, role;  // role: free, fixed, per_experiment
    double value = kNaN;
    double std_error = kNaN;  // NaN where none
  };
  std::vector<Parameter> parameters;  // results.json "parameters", in its order
  // The last stage with a correlation: its matrix over `correlation_names` (NaN where
  // undetermined; square, ones on the diagonal) and its bootstrap's replicates, if any.
  std::vector<std::string> correlation_names;
  Eigen::MatrixXd correlation;
  std::vector<std::string> replicate_names;
  std::vector<std::vector<double>> replicate_values;  // NaN where a replicate has none
  // The last model stage (one with estimates and a model: the final values' stage).
  bool has_model_stage = false;
  double integration_step = kNaN;  // the step it integrated with (s), NaN where not recorded
  double max_step = kNaN;          // its integration.max_step
  std::map<std::string, std::string> interpolation;  // per input
  struct Metric {
    std::string output, unit;
    double rmse = kNaN, samples = kNaN;
  };
  std::vector<Metric> fit_metrics;  // its fit, per experiment and output, in the data's units
  std::vector<std::string> free_initial_states;  // the states it estimated a start of
  std::vector<ProcessNoise> process_noise;       // a filter-error stage's, identified with it
  std::vector<ZigzagEntry> zigzags;              // "zigzags": every zigzag record's figures
};

// The run whose outputs are in `out_folder` (its results.json); a publication a killed run
// left is finished first. False with a message naming the file and the key.
bool ReadRunDocument(const std::string& out_folder, RunDocument* document, std::string* error);

// The same of a finished run in memory: what ReadRunDocument gives of the results.json it
// writes (path: the run's config).
RunDocument RunDocumentOf(const RunConfig& config, const RunResult& result);

}  // namespace vesselid
