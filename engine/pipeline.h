// A staged identification run: the stages of a config executed in order, each building its
// output-error problem from its experiments and parameter declarations.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/config.h"
#include "engine/stage.h"

namespace vesselid {

// One estimated or fixed quantity as reported.
struct Estimate {
  std::string name;
  std::string kind;        // parameter or initial_state
  std::string role;        // free, fixed, per_experiment
  std::string experiment;  // empty when shared
  double value = 0.0;
  double start = 0.0;
  double std_error = 0.0;  // NaN when unknown or fixed
  double lower = 0.0, upper = 0.0;
};

struct StageResult {
  std::string name;
  StageSummary summary;
  std::vector<Estimate> estimates;
  std::vector<std::string> correlation_names;  // free variables, matrix order
  Eigen::MatrixXd correlation;
};

struct RunResult {
  std::vector<StageResult> stages;
  double time_seconds = 0.0;
};

// Observer told when a stage starts and ends (progress output); may be empty.
using StageObserver = std::function<void(const StageResult* finished, const std::string& next)>;

// Runs every stage. On failure nothing is returned but the message naming the stage and cause.
bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const StageObserver& observer = nullptr);

// Recorded data by file, so that stages sharing an experiment read it once.
using TrajectoryCache = std::map<std::string, Trajectory>;

// Reads and prepares one stage's experiments (used by RunIdentification and by tools).
bool PrepareStageExperiments(const RunConfig& config, const StageConfig& stage,
                             TrajectoryCache* cache, std::vector<Experiment>* experiments,
                             std::string* error);

}  // namespace vesselid
