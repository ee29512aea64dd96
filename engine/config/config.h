// A run as a YAML config describes it, parsed at the edge into plain structs.
//
//   model:       {family: nomoto, type: second_order, ...family keys}
//   simulation:  family-specific description of synthetic experiments (`vesselid simulate`)
//   experiments: [{name, file, inputs, outputs, interpolation, weights, initial_state,
//                  degrees, window}]
//   stages:      [{name, type, least_squares, model, experiments, validation, outputs,
//                  parameters,
//                  free_initial_states, loss, integration, normalize_by_length, continuation,
//                  global, local, uncertainty}]
//   fusion:      inverse_variance | mean | information (fusion.h)
//   final_validation: {experiments, outputs, model, free_initial_states}
//   study:       {seed, threads, profile, monte_carlo, starts, partitions}  (`vesselid study`,
//                 study_options.h)
//
// A stage's `model` map overrides keys of the run's `model` map (e.g. active DOFs). A
// parameter without `start` starts from its latest estimate in an earlier stage (else the
// model default); parameters a stage does not list are held at that value.
//
// Every key is checked; an unknown key, a name the model does not have, inverted bounds or a
// start outside them is an error naming file, line and key.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/run/fusion.h"
#include "engine/regression/least_squares.h"
#include "engine/regression/regression_data.h"
#include "engine/config/model_registry.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/parameter.h"
#include "engine/study/partition_study.h"
#include "engine/study/study_options.h"
#include "engine/solve/stage.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

struct StageConfig {
  // output_error: simulate and compare (the default); least_squares: equation-error regression
  // of the model's derivative form (least_squares.h), its estimate starting the next stage;
  // step_regression: seed 004's damping and inertia regression on steady states and steps
  // (step_regression.h), for models with a damping-inertia form.
  enum class Kind { kOutputError, kLeastSquares, kStepRegression };
  Kind kind = Kind::kOutputError;
  StageOptions options;
  LeastSquaresOptions least_squares;
  StepRegressionOptions step_regression;
  // How records become regression data (least-squares stages, and the velocity metrics of
  // any stage's validation when the model has an equation-error form).
  RegressionDataOptions regression_data;
  // The stage's own restriction of the model (e.g. active DOFs); null: the run's model.
  std::shared_ptr<const ModelHandle> model;
  std::vector<std::string> experiments;  // names from RunConfig::experiments
  // Held-out experiments simulated after the stage (its free initial states estimated first).
  std::vector<std::string> validation;
  std::vector<ParameterSpec> parameters;
  OutputErrorOptions problem;
  ExperimentOptions experiment;  // compared outputs, step bound, length normalisation
  // Segment lengths (s, increasing) the stage is solved with first, each phase starting the
  // next; empty: the stage is solved once on its experiments as configured.
  std::vector<double> continuation;
};


// Held-out runs simulated with the final parameters after the last stage.
struct FinalValidationConfig {
  std::vector<std::string> experiments;
  std::vector<std::string> free_initial_states;  // estimated with the final parameters held
  std::shared_ptr<const ModelHandle> model;  // null: the run's model
  ExperimentOptions experiment;
};

struct RunConfig {
  std::string path;
  std::string description;
  std::string family;
  std::shared_ptr<const ModelHandle> model;
  const ModelFamily* model_family = nullptr;
  YAML::Node simulation;  // handed to the family's simulator, parsed there
  std::vector<ExperimentSpec> experiments;
  std::vector<StageConfig> stages;
  FusionRule fusion = FusionRule::kInverseVariance;
  bool has_final_validation = false;
  FinalValidationConfig final_validation;
  // Damping and inertia surfaces written by `run` for models with a damping-inertia form
  // (`surfaces: {<state>: [lower, upper, points], <state>: [...]}`); empty: none.
  SurfaceGrid surfaces;
  // Sensitivity studies (`vesselid study`); empty when the config has no study section.
  StudyConfig study;

  const ExperimentSpec* FindExperiment(const std::string& name) const;
};

// Experiment files are resolved against data_dir when it is not empty, else against the
// config file's folder.
bool LoadRunConfig(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, RunConfig* config, std::string* error);

}  // namespace vesselid
