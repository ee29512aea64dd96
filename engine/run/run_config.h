// A staged run as plain data: the model, the recorded experiments, the stages in order, how
// shared parameters are fused and what is validated at the end. No YAML and no studies: a
// config file is parsed into this at the edge (config/config.h), and a program can fill it
// in C++ (examples/staged_run.cc).
//
// A stage's parameter without a start (start_from_previous) starts from its latest estimate
// in an earlier stage (else the model default); parameters a stage does not list are held at
// that value.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/base/statistics.h"
#include "engine/base/work_limits.h"
#include "engine/model/damping_inertia_form.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/regression/least_squares.h"
#include "engine/regression/regression_data.h"
#include "engine/run/fusion.h"
#include "engine/run/reference_model.h"
#include "engine/run/search_horizons.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/parameter.h"
#include "engine/solve/stage.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// Experiments (segments) of an output-error stage that its fit does not serve: a cost above
// median + threshold x 1.4826 MAD of the experiments' RMS costs, or initial states more than
// 3 standard errors from the data's guess. Always named in a note; `downweight` refines again
// with each such experiment's weights scaled by median / its RMS cost, `drop` without them.
struct OutlierOptions {
  enum class Action { kNote, kDownweight, kDrop };
  Action action = Action::kNote;
  double threshold = 5.0;
};

// An experiment's RMS cost above which it is an outlier: median + threshold x 1.4826 MAD of
// the costs, and never below (1 + threshold / kOutlierFloorScale) x the median (twice the
// median at the default threshold 5). With few runs whose costs are all alike (five within
// 3.5 %) the MAD is tiny and the first term alone named a correct run.
inline constexpr double kOutlierFloorScale = 5.0;
inline double OutlierLimit(const std::vector<double>& rms, double threshold) {
  const double median = UpperMedian(rms, 0.0);
  std::vector<double> deviations;
  for (double r : rms) deviations.push_back(std::abs(r - median));
  return std::max(median + threshold * 1.4826 * UpperMedian(deviations, 0.0),
                  (1.0 + threshold / kOutlierFloorScale) * median);
}

// What held-out runs do with the per-experiment parameters (a rudder bias per run) that have
// no value for them (`per_experiment:`): estimate their own with the other parameters held
// (fit), or take the parameter's start (hold).
enum class HeldOutPerExperiment { kFit, kHold };

const char* HeldOutPerExperimentToString(HeldOutPerExperiment mode);  // "fit", "hold"
bool StringToHeldOutPerExperiment(const std::string& text, HeldOutPerExperiment* mode);

// How a held-out run starts (`held_out: {start, burn_in, implausible_sds}` of a stage and of
// final_validation). A held-out run is a prediction: with `measured` (the default) the states
// the record measures start at their measured values, and what it does not measure (the
// listed free states that are not outputs, the run's own parameters) is estimated on a
// burn-in at its start, which is not scored. With `refitted` every listed state is estimated
// on the whole run, which is scored whole; the figures from the measured start are reported
// beside it and a refitted measured state more than `implausible_sds` noise SDs from its
// measurement is a finding.
struct HeldOutStart {
  enum class Mode { kMeasured, kRefitted };
  Mode mode = Mode::kMeasured;
  // Burn-in, s; 0: kBurnInShare of the run, at least kMinBurnInIntervals sample intervals.
  double burn_in = 0.0;
  double implausible_sds = 5.0;
  InitialStatePrior prior;  // the stage's (or final_validation's) initial_state_prior
};
inline constexpr double kBurnInShare = 0.1;
inline constexpr int kMinBurnInIntervals = 10;

const char* HeldOutStartModeToString(HeldOutStart::Mode mode);  // "measured", "refitted"
bool StringToHeldOutStartMode(const std::string& text, HeldOutStart::Mode* mode);

// A model's options as a config gives them: each key of the `model` map but `family`, its value
// as YAML text ("second_order", "[surge, sway, yaw]"), so that the model can be made again
// (ModelRegistry::MakeModel) from results.json alone.
using ModelOptions = std::map<std::string, std::string>;

struct StageConfig {
  // output_error: simulate and compare (the default); least_squares: equation-error regression
  // of the model's derivative form (least_squares.h), its estimate starting the next stage;
  // step_regression: seed 004's damping and inertia regression on steady states and steps
  // (step_regression.h), for models with a damping-inertia form.
  enum class Kind { kOutputError, kLeastSquares, kStepRegression };
  Kind kind = Kind::kOutputError;
  StageOptions options;  // options.name is the stage's name
  LeastSquaresOptions least_squares;
  StepRegressionOptions step_regression;
  // How records become regression data (least-squares stages, and the velocity metrics of
  // any stage's validation when the model has an equation-error form).
  RegressionDataOptions regression_data;
  // The stage's own restriction of the model (e.g. active DOFs); null: the run's model.
  std::shared_ptr<const ModelHandle> model;
  // With `model`: its options (ModelOptions), the run's with the stage's keys replaced.
  ModelOptions model_options;
  std::vector<std::string> experiments;  // names from RunConfig::experiments
  // Held-out experiments simulated after the stage (its free initial states estimated first).
  std::vector<std::string> validation;
  HeldOutPerExperiment validation_per_experiment = HeldOutPerExperiment::kFit;
  HeldOutStart held_out;  // how the validation runs start (prior: the stage's own)
  std::vector<ParameterSpec> parameters;
  OutputErrorOptions problem;
  ExperimentOptions experiment;  // compared outputs, step bound, length normalisation
  // `weights:` noise (per-channel noise model, noise_weights.h) or given (the experiments'
  // configured weights); kDefault: noise when the stage compares two or more outputs
  // (stage_weights.h). `normalize_by_length_set`: the stage sets normalize_by_length itself.
  enum class Weights { kDefault, kNoise, kGiven };
  Weights weights = Weights::kDefault;
  bool normalize_by_length_set = false;
  // Segment lengths (s, increasing) the stage is solved with first, each phase starting the
  // next; empty: the stage is solved once on its experiments as configured.
  std::vector<double> continuation;
  // Segment lengths the multistart global start searches on when the stage has no
  // continuation of its own (`global: {horizons: ...}`, search_horizons.h).
  SearchHorizons search_horizons;
  // Initial states the continuation phases estimate besides the stage's own
  // (free_initial_states): a search on pieces frees those the data do not measure.
  std::vector<std::string> continuation_free_states;
  OutlierOptions outliers;
  // One-step-ahead and free-run velocity metrics of the held-out runs (velocity_validation.h)
  // for a model with an equation-error form; `velocity_validation: false` leaves them out.
  bool velocity_validation = true;
};

// "output_error", "least_squares", "step_regression" (a config's stage `type`).
const char* StageKindToString(StageConfig::Kind kind);
bool StringToStageKind(const std::string& text, StageConfig::Kind* kind);

// Held-out runs simulated with the final parameters after the last stage.
struct FinalValidationConfig {
  std::vector<std::string> experiments;
  std::vector<std::string> free_initial_states;  // estimated with the final parameters held
  std::shared_ptr<const ModelHandle> model;      // null: the run's model
  ExperimentOptions experiment;
  // Per-experiment parameters of the last stage that estimated them.
  HeldOutPerExperiment per_experiment = HeldOutPerExperiment::kFit;
  HeldOutStart held_out;  // with final_validation's initial_state_prior
  // `reference`: another run's model flown beside the final values (reference_model.h);
  // folder empty when none.
  ReferenceModel reference;
};

// Which estimate a stage that is worse on its held-out data than its start leaves to the
// later stages and the final values (`final:`): the better one (its start), or its own.
enum class FinalChoice { kBestValidation, kLast };

const char* FinalChoiceToString(FinalChoice choice);  // "best_validation", "last"
bool StringToFinalChoice(const std::string& text, FinalChoice* choice);

struct RunConfig {
  std::string path;  // the config file (messages, checkpoint fingerprint); may be empty
  std::string description;
  std::string family;  // the model family's name, as reported
  std::shared_ptr<const ModelHandle> model;
  ModelOptions model_options;  // the `model` map's keys but family, each value as YAML text
  std::vector<ExperimentSpec> experiments;  // files resolved to paths
  std::vector<StageConfig> stages;
  FusionRule fusion = FusionRule::kInverseVariance;
  FinalChoice final_choice = FinalChoice::kBestValidation;
  bool has_final_validation = false;
  FinalValidationConfig final_validation;
  // The final validation's velocity metrics, and every stage's default (StageConfig).
  bool velocity_validation = true;
  // Damping and inertia surfaces written by `run` for models with a damping-inertia form
  // (`surfaces: {<state>: [lower, upper, points], <state>: [...]}`); empty: none.
  SurfaceGrid surfaces;
  WorkLimits limits;  // the config's `limits` (also copied into every experiment and stage)
  // Named lists of experiments (`sets:`, config/experiment_sets.h); the stages' and final
  // validation's lists above are already expanded.
  std::map<std::string, std::vector<std::string>> experiment_sets;

  const ExperimentSpec* FindExperiment(const std::string& name) const;
  // The model a stage is solved with: its own restriction, else the run's.
  const ModelHandle& StageModel(const StageConfig& stage) const {
    return stage.model ? *stage.model : *model;
  }
  const ModelOptions& StageModelOptions(const StageConfig& stage) const {
    return stage.model ? stage.model_options : model_options;
  }
};

}  // namespace vesselid
