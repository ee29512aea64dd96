// A run's identified model as it is taken out (`vesselid export`): the family and options that
// make it again, its states, inputs and outputs with units, every parameter's value (the run's
// final values; the model's defaults for those no stage estimated), the covariance of the
// estimated ones, ensemble members drawn from it, and the integration step the run used.
// Written as model.json (the `json` format, and the FMU's resources/model.json); read back by
// the FMU's runtime and by tools.
#pragma once

#include <string>
#include <vector>

#include "Eigen/Core"
#include "engine/config/model_registry.h"
#include "engine/run/run_config.h"
#include "engine/output/run_document.h"
#include "nlohmann/json.hpp"

namespace vesselid {

struct ExportedVariable {
  std::string name, unit;
};

struct ExportedModel {
  std::string family;
  std::string model;  // the model's name (ModelInfo::name)
  ModelOptions options;
  std::vector<ExportedVariable> states, inputs, outputs, parameters;
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
  // RK4 steps of at most this length (s) within each sample interval; 0: one step per
  // interval (the run's default, the median sample interval, on regularly sampled data).
  double max_step = 0.0;
  // Per input: how the run interpolated it between samples (zero_order_hold, linear, cubic).
  std::vector<std::string> interpolation;
  std::string results;  // the results.json it came from
};

// The model of `family` with `options` (its variables, units, default parameter values, no
// standard errors, no covariance, no ensemble); null with a message when it cannot be made.
std::shared_ptr<const ModelHandle> MakeExportedModel(const ModelRegistry& registry,
                                                     const std::string& family,
                                                     const ModelOptions& options,
                                                     ExportedModel* model, std::string* error);

// The model of the run whose outputs are in `out_folder` (its results.json, read once by
// run_document.h), with `members` ensemble members drawn with `seed`. False with a message
// naming the file and key. `document` (may be null) gets what the run's results.json says.
bool ReadExportedModel(const std::string& out_folder, const ModelRegistry& registry, int members,
                       unsigned seed, ExportedModel* model, std::string* error,
                       RunDocument* document = nullptr);

// The same from a run's document.
bool ExportedModelOf(const RunDocument& document, const ModelRegistry& registry, int members,
                     unsigned seed, ExportedModel* model, std::string* error);

// model.json and back.
nlohmann::json ExportedModelToJson(const ExportedModel& model);
bool ExportedModelFromJson(const nlohmann::json& j, ExportedModel* model, std::string* error);

// Draws `members` full parameter vectors from N(values, covariance) (a Cholesky factor of the
// covariance, its non-positive directions left out) with a fixed seed.
std::vector<std::vector<double>> DrawEnsemble(const ExportedModel& model, int members,
                                              unsigned seed);

}  // namespace vesselid
