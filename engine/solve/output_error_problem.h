// The output-error problem of one stage: every experiment simulated over its whole length,
// one Ceres residual block per experiment, every scalar unknown its own parameter block.
//
//   min over p, x0_e   1/2 sum_e sum_i rho( (w_i (y(t_i; p, x0_e, u_e) - y_i))^2 )
//
// Shared parameters are one block used by every experiment's residual block; per-experiment
// parameters and initial states are separate blocks per experiment (the sparse structure
// Ceres' Schur and SuiteSparse solvers exploit). Fixed quantities are constant blocks.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ceres/ceres.h"
#include "engine/model/disturbance.h"
#include "engine/model/evaluation_cache.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/solve/parameter.h"

namespace vesselid {

// One scalar unknown of the problem.
struct Variable {
  // kInputCorrection: one low-frequency correction value of a noisy input (input_noise.h);
  // kNoise: a parameter of the filter-error method's disturbance model (disturbance.h).
  enum class Kind { kParameter, kInitialState, kInputCorrection, kNoise };
  std::string name;  // "T1", "delta_0[run2]", "x0.psi[run2]", "c.delta#3[run2]"
  Kind kind = Kind::kParameter;
  int index = 0;        // parameter, state or input index in the model
  int experiment = -1;  // -1: shared by all experiments
  ParameterRole role = ParameterRole::kFree;
  double scale = 1.0;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool free = true;
  double* block = nullptr;  // holds value / scale

  double value() const { return *block * scale; }
  // The block is left as it is when it already gives v: v / scale need not give the block's
  // bits back, and setting the values a solve ended at must not move it (the evaluation
  // cache answers at bit-identical blocks only).
  void set_value(double v) const {
    if (value() != v) *block = v / scale;
  }
  bool bounded() const { return std::isfinite(lower) && std::isfinite(upper); }
};

// A free initial state is tied to the data's guess of it (Experiment::initial_state_guess)
// by a prior that counts as one sample,
//   r = prior_weight (x0 - guess) / (scale sigma_guess),
// and kept within guess +- bounds B, B = `bounds` x max(1.4826 MAD of the guesses of that
// state over the problem's experiments, half their largest magnitude, 10 x median sigma),
// so that it cannot float off to absorb what the model does not explain.
struct InitialStatePrior {
  enum class Apply { kSegments, kAll, kOff };  // kSegments: experiments cut from a record
  Apply apply = Apply::kSegments;
  double scale = 1.0;   // multiplies each guess's standard error
  double bounds = 3.0;  // 0: no bounds
};

struct OutputErrorOptions {
  std::vector<std::string> free_initial_states;  // estimated per experiment
  InitialStatePrior prior;
  std::string loss = "none";                     // none, huber, cauchy, soft_l1, arctan
  double loss_scale = 1.0;                       // residual size where the loss bends
  // Each experiment's cost keeps its last evaluation of each kind and copies it when asked
  // again at the same values (evaluation_cache.h); off: every evaluation simulates.
  bool evaluation_cache = true;
  // method filter_error: each experiment's cost is the Kalman filter's innovations likelihood
  // (filter_error_cost.h) with the disturbance's parameters as shared variables (Kind::kNoise,
  // after every other variable); method auto is the stage's to resolve before (a problem
  // treats it as output error).
  DisturbanceSpec disturbance;
  // Starts a noise parameter takes instead of the layout's (by name, e.g. from an earlier
  // stage or candidate).
  std::map<std::string, double> noise_starts;
};

class OutputErrorProblem {
 public:
  // `parameters` names model parameters; unnamed ones are fixed at the model's default.
  // Errors name the offending parameter, state or experiment.
  static std::unique_ptr<OutputErrorProblem> Create(const ModelHandle* model,
                                                    std::vector<Experiment> experiments,
                                                    const std::vector<ParameterSpec>& parameters,
                                                    const OutputErrorOptions& options,
                                                    std::string* error);

  // An independent copy at the current values and channel weights (one per thread of a
  // parallel search); nullptr only if memory runs out.
  std::unique_ptr<OutputErrorProblem> Clone() const;

  ceres::Problem* problem() { return problem_.get(); }
  const ModelHandle& model() const { return *model_; }
  const std::vector<Variable>& variables() const { return variables_; }
  const std::vector<Experiment>& experiments() const { return experiments_; }
  // Rows of the experiments' residual blocks (initial-state priors not counted): the data
  // samples, twice that under the filter-error method (two residuals per sample).
  int num_residuals() const;
  int num_samples() const;  // data samples

  // The filter-error method: whether this problem is one, its disturbance's layout, and the
  // noise parameters' current values (layout order, physical units).
  bool filter_error() const { return filter_error_; }
  const DisturbanceLayout& disturbance() const { return layout_; }
  std::vector<double> NoiseValues() const;
  // The filter run of experiment e at the current values (filter_innovations.h); false if it
  // diverges. `steps`: the k of the k-step-ahead predictions (0: none).
  bool RunFilter(int e, int steps, FilterRun* run) const;
  // The records' operating range at the current values (operating_range.h): per state the
  // largest |x| of the experiments' simulations, then per input its smallest and largest value.
  std::vector<double> OperatingRange() const;
  // The likelihood's score and Fisher information of experiment e at the current values
  // (omitted_terms.h) over the unknowns free for it (its free model parameters and initial
  // states, the free noise parameters: `free` gets their names) and then the candidate terms,
  // all at c = 0. False if the filter diverges or this is not a filter-error problem.
  bool ScoreOmittedTerms(int e, const std::vector<OmittedTerm>& terms, OmittedTermScore* score,
                         std::vector<std::string>* free) const;
  // -log L of the innovations summed over the experiments at the current values (NaN when a
  // filter diverges or this is not a filter-error problem).
  double NegativeLogLikelihood() const;
  // Sets the likelihood residuals' offsets so that J'J is the Fisher information at the
  // current values (filter_error_cost.h) and returns the previous ones, for RestoreOffsets.
  // `margin` > 0 sets min log S + c_j = 1 + margin instead: room for the variances to fall
  // while solving, at a Gauss-Newton curvature of log S at most 1 + margin times too low.
  std::vector<double> CentreLikelihood(double margin = 0.0);
  // min over the samples of log S_i + c_j at the current values: below 0 the likelihood's
  // log-variance rows are clamped (NaN when a filter diverges or this is output error).
  double LowestLikelihoodTerm() const;
  // Moves each noise parameter in turn to the best of its value times 10^-4 .. 10^2 (within
  // its bounds) by the likelihood at the other values held (a few filter runs in double): a
  // start decades off costs the solver tens of iterations crawling in linear steps.
  void ScanNoiseStarts();
  // Per model output, the lowest log S over the samples (+inf without samples; empty when a
  // filter diverges).
  std::vector<double> LowestLogVariances() const;
  void RestoreOffsets(const std::vector<double>& offsets) {
    offsets_->c = offsets;
    ++offsets_->revision;
  }
  // The residual blocks of the experiments, in experiment order (without the priors).
  const std::vector<ceres::ResidualBlockId>& data_residual_blocks() const { return data_blocks_; }
  int num_free() const;

  // Model parameters, initial state and input corrections (Experiment::input_corrections
  // order) as experiment e sees them (physical units).
  std::vector<double> ParametersOf(int e) const;
  std::vector<double> InitialStateOf(int e) const;
  std::vector<double> InputCorrectionsOf(int e) const;

  // Values of all variables (physical) and back; used to restart from candidates.
  std::vector<double> Values() const;
  void SetValues(const std::vector<double>& values);

  // Re-weights every experiment's output channels (channel_weights.h; `weight` per model
  // output), priors included; the next solve or evaluation sees the new weights.
  void SetChannelWeights(const std::vector<double>& weight);

  // 1/2 sum r^2 at the current values; false if any simulation diverges.
  bool Cost(double* cost);

  // Every experiment's channel weights (Experiment::channel_weight), experiment order.
  std::vector<std::vector<double>> ChannelWeights() const;
  // Cost() with each experiment's channels weighted by `weights` (as ChannelWeights returned
  // them), the current weights restored after.
  bool CostWithChannelWeights(const std::vector<std::vector<double>>& weights, double* cost);

  // Simulations and cache hits of the experiments' costs so far.
  const EvaluationCounts& evaluation_counts() const { return *counts_; }
  // Frees the experiments' cached evaluations (a Jacobian each); later evaluations fill the
  // caches again.
  void ReleaseEvaluationCaches();

 private:
  OutputErrorProblem() = default;
  // The filter-error method's disturbance layout, its initial variances and offsets.
  static bool BuildLayout(const std::vector<ParameterSpec>& specs,
                          const OutputErrorOptions& options, OutputErrorProblem* p,
                          std::string* error);
  // Prior residuals and bounds of the free initial states (InitialStatePrior).
  static void AddInitialStatePriors(const InitialStatePrior& prior, OutputErrorProblem* p);
  // Prior residuals of the input corrections: r = prior_weight c / sigma_c (input_noise.h).
  static void AddInputCorrectionPriors(OutputErrorProblem* p);

  const ModelHandle* model_ = nullptr;
  std::vector<ParameterSpec> specs_;  // as created, for Clone
  OutputErrorOptions options_;
  std::vector<Experiment> experiments_;
  std::unique_ptr<ceres::LossFunction> loss_;
  std::unique_ptr<ceres::Problem> problem_;
  std::vector<ceres::ResidualBlockId> data_blocks_;
  std::unique_ptr<EvaluationCounts> counts_ = std::make_unique<EvaluationCounts>();
  std::vector<std::unique_ptr<EvaluationCache>> caches_;  // per experiment (if enabled)
  bool filter_error_ = false;
  DisturbanceLayout layout_;
  std::unique_ptr<FilterOffsets> offsets_ = std::make_unique<FilterOffsets>();
  std::vector<std::vector<double>> initial_variance_;  // per experiment, per state (filter P0)
  std::vector<double> storage_;  // every block, reserved once: stable, ordered addresses
  std::vector<Variable> variables_;
  // block_of_[e][j]: variable index of block j (parameters, states, then input corrections) of
  // experiment e.
  std::vector<std::vector<int>> block_of_;
};

}  // namespace vesselid
