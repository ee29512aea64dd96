// One output-error stage of a run as the studies vary it: its parameter specs as the run
// carries them into the stage, its experiments prepared from the data once, and solves of
// variants (other data, other starts, a parameter held) with one thread per solve.
//
// Studies solve the stage as configured (global start, extra refinements) but without its
// continuation phases; a stage that needs them is studied from starts close enough not to.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/base/json_number.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/solve/noise_weights.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "nlohmann/json.hpp"

namespace vesselid {

struct StudyStage {
  const RunConfig* config = nullptr;
  const StageConfig* stage = nullptr;
  const ModelHandle* model = nullptr;
  std::vector<ParameterSpec> specs;     // every model parameter, model order
  std::vector<Experiment> experiments;  // the stage's, from the data
  StageOptions options;                 // the stage's, single-threaded
  std::vector<int> free;                // model indices of the free shared parameters
  std::vector<std::string> free_names;
  // With PrepareStudyStage(..., solve = true): every unknown's value (by variable name) as
  // the run's own solve of the stage found it, continuation and global start included.
  std::map<std::string, double> run_optimum;
  std::map<std::string, double> run_std_errors;  // and its standard errors (NaN: none)
  // The stage's records as read and prepared once (by configured experiment name), from
  // which variants of the data rebuild its experiments (PrepareExperiments).
  TrajectoryCache records;
  // The stage weighs its channels by their estimated noise (stage_weights.h): every solve
  // iterates the noise model (noise_weights.h) as the run does.
  bool noise_weights = false;

  // Starts of the free parameters, in `free` order.
  std::vector<double> FreeStarts() const;
};

// The output-error stage called `name` (empty: the run's last one), after the stages before
// it ran (and the stage itself with `solve`). Errors name the stage.
bool PrepareStudyStage(const RunConfig& config, const std::string& name, StudyStage* stage,
                       std::string* error, bool solve = false);

// A solved variant: problem at its optimum and the stage summary.
struct StudySolve {
  std::unique_ptr<OutputErrorProblem> problem;
  StageSummary summary;
  NoiseModel noise;  // with StudyStage::noise_weights
  bool usable = false;
  std::string message;

  // Free parameter values and standard errors (NaN where unknown), in StudyStage::free order.
  std::vector<double> Values(const StudyStage& stage) const;
  std::vector<double> StdErrors(const StudyStage& stage) const;
};

// Solves the stage on `experiments` from `specs`. `start` (optional) gives start values by
// variable name (as Variable::name); parameters whose spec is fixed keep their spec value.
// Never fails the caller: an unusable solve says why.
StudySolve SolveStudyStage(const StudyStage& stage, std::vector<Experiment> experiments,
                           const std::vector<ParameterSpec>& specs, const StageOptions& options,
                           const std::map<std::string, double>* start = nullptr);

// Every unknown's value by variable name.
std::map<std::string, double> ValuesByName(const OutputErrorProblem& problem);

// Per-sample noise-free outputs of the stage's experiments simulated with `parameters`
// (model order) from the initial states the stage starts from (estimated ones from their
// guesses): clean[e][i] belongs to experiments[e].samples[i]. With `values` (by variable
// name, e.g. StudyStage::run_optimum) the per-experiment parameters and estimated initial
// states named there take those values. False if one diverges.
bool SimulateSamples(const StudyStage& stage, const std::vector<double>& parameters,
                     std::vector<std::vector<double>>* clean, std::string* error,
                     const std::map<std::string, double>* values = nullptr);

}  // namespace vesselid
