// The product of a run: its identified model. The family and options that make it again, its
// states, inputs and outputs with units, every parameter's value (the run's final values; the
// model's defaults for those no stage estimated), the covariance of the estimated ones,
// ensemble members drawn from it, and how the run integrated (step bound, interpolation).
//
// One type for every user of a run's model: `export` (model.json, C, FMU), `predict`,
// `design`, a reference model and Python's `RunResult.model`. Built in memory from the run
// (IdentifiedModelOf(config, result)) or from a run's results.json (run_document.h; the
// folder reader is export/run_folder_model.h); both give the same model.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Eigen/Core"
#include "engine/model/model_handle.h"
#include "engine/output/process_noise.h"
#include "engine/output/run_document.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

struct ModelVariable {
  std::string name, unit;  // the model's (SI) unit
};

struct IdentifiedModel {
  std::string family;
  std::string model;  // the model's name (ModelInfo::name)
  ModelOptions options;
  // The model made from family and options; null for a model read from model.json.
  std::shared_ptr<const ModelHandle> handle;
  std::vector<ModelVariable> states, inputs, outputs, parameters;
  // Per parameter: the run's final values; the model's defaults where no stage estimated one
  // or where it was estimated per experiment (a run's own bias).
  std::vector<double> values;
  std::vector<double> std_errors;  // per parameter; NaN where not estimated
  // Over the estimated parameters (covariance_names, a subset of parameters): from the
  // correlation of the last stage that has one and the final standard errors,
  // C_ij = r_ij s_i s_j; a parameter the correlation does not cover is uncorrelated.
  std::vector<std::string> covariance_names;
  Eigen::MatrixXd covariance;
  // Full parameter vectors (member k + 1 is ensemble[k]; member 0 is `values`): draws from
  // N(values, covariance) for the estimated parameters, the rest at their values; or, where
  // the run's covariance is a bootstrap's, its replicates' estimates.
  std::vector<std::vector<double>> ensemble;
  std::string ensemble_source = "covariance";  // or "bootstrap"
  unsigned ensemble_seed = 0;                  // of the draws
  // RK4 steps of at most this length (s) within each sample interval; 0: the median sample
  // interval (the run's default).
  double max_step = 0.0;
  // Per input: how the run interpolated it between samples (zero_order_hold, linear, cubic).
  std::vector<std::string> interpolation;
  // Inputs, outputs and states the run's data gave in degrees (the first experiment's
  // `degrees:`): what a user's tables hold in degrees. Empty for a model read from a file.
  std::vector<std::string> degree_names;
  // The process noise the final model's stage identified with it (a filter-error stage's
  // `process:`), on states of this model; `predict` flies it (process_noise.h).
  std::vector<ProcessNoise> process_noise;
  std::string results;  // where it came from: the results.json, or the run's config
};

// The model `handle` made of `family` and `options`, described: its variables, units and
// default parameter values, no standard errors, no covariance, no ensemble.
void DescribeModel(std::shared_ptr<const ModelHandle> handle, const std::string& family,
                   const ModelOptions& options, IdentifiedModel* model);

// The model a run's document describes, made by `handle` (family and options as the
// document says), with `members` ensemble members drawn with `seed` (members > 0: refused
// where the covariance is none, as a run whose correlations are not finite, symmetric and
// within [-1, 1] may report). False with a message naming the document and key.
bool IdentifiedModelOf(const RunDocument& document, std::shared_ptr<const ModelHandle> handle,
                       int members, unsigned seed, IdentifiedModel* model, std::string* error);

// The model of a finished run, in memory: what the run's results.json would give.
bool IdentifiedModelOf(const RunConfig& config, const RunResult& result, int members,
                       unsigned seed, IdentifiedModel* model, std::string* error);

// Draws `members` full parameter vectors from N(values, covariance) (a Cholesky factor of the
// covariance, its non-positive directions left out) with a fixed seed.
std::vector<std::vector<double>> DrawEnsemble(const IdentifiedModel& model, int members,
                                              unsigned seed);

}  // namespace vesselid
