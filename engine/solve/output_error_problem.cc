#include "engine/solve/output_error_problem.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/base/check.h"
#include "engine/base/statistics.h"
#include "engine/model/channel_weights.h"
#include "engine/model/operating_range.h"

namespace vesselid {
namespace {

bool MakeLoss(const OutputErrorOptions& options, std::unique_ptr<ceres::LossFunction>* loss,
              std::string* error) {
  const std::string& type = options.loss;
  const double a = options.loss_scale;
  if (type == "none") {
    loss->reset();
  } else if (!(a > 0.0)) {
    *error = "loss scale must be positive";
    return false;
  } else if (type == "huber") {
    loss->reset(new ceres::HuberLoss(a));
  } else if (type == "cauchy") {
    loss->reset(new ceres::CauchyLoss(a));
  } else if (type == "soft_l1") {
    loss->reset(new ceres::SoftLOneLoss(a));
  } else if (type == "arctan") {
    loss->reset(new ceres::ArctanLoss(a));
  } else {
    *error = "unknown loss '" + type + "' (none, huber, cauchy, soft_l1, arctan)";
    return false;
  }
  return true;
}

}  // namespace

namespace {

// r = a (x - guess) on a block holding x / scale, a = prior_weight x factor; the experiment's
// prior weight is read at each evaluation (channel re-weighting changes it, SetChannelWeights).
class PriorCost final : public ceres::SizedCostFunction<1, 1> {
 public:
  PriorCost(const double* prior_weight, double factor, double guess, double scale)
      : prior_weight_(prior_weight), factor_(factor), guess_(guess), scale_(scale) {}
  bool Evaluate(double const* const* x, double* residual, double** jacobian) const override {
    const double weight = *prior_weight_ * factor_;
    residual[0] = weight * (x[0][0] * scale_ - guess_);
    if (jacobian != nullptr && jacobian[0] != nullptr) jacobian[0][0] = weight * scale_;
    return true;
  }

 private:
  const double* prior_weight_;
  double factor_, guess_, scale_;
};

}  // namespace

namespace {

std::vector<double> NoiseScales(const DisturbanceLayout& layout) {
  std::vector<double> scales;
  for (const NoiseParameter& p : layout.parameters) scales.push_back(p.start);
  return scales;
}

}  // namespace

bool OutputErrorProblem::BuildLayout(const std::vector<ParameterSpec>& specs,
                                     const OutputErrorOptions& options, OutputErrorProblem* p,
                                     std::string* error) {
  const ModelInfo& info = p->model_->info();
  const size_t ny = info.outputs.size(), nx = info.states.size();
  DisturbanceScales scales;
  std::vector<double> power(ny, 0.0), count(ny, 0.0);
  scales.state_magnitude.assign(nx, 0.0);
  std::vector<double> parameters;
  for (const ParameterSpec& spec : specs) parameters.push_back(spec.start);
  std::vector<double> intervals;
  p->initial_variance_.clear();
  for (const Experiment& e : p->experiments_) {
    for (size_t j = 0; j < ny; ++j) {
      if (e.output_sample_count[j] == 0) continue;
      count[j] += e.output_sample_count[j];
      power[j] += e.channel_noise_power[j];
    }
    const std::vector<double>& x0 =
        e.initial_state_guess.size() == nx ? e.initial_state_guess : e.initial_state;
    p->model_->StateLimits(e, parameters.data(), x0.data(), scales.state_magnitude.data());
    for (int k = 0; k + 1 < e.num_nodes(); ++k) {
      intervals.push_back(e.node_time[k + 1] - e.node_time[k]);
    }
    // P0: the start's variance where the initial state is not estimated (NaN: exact).
    std::vector<double> variance(nx, 0.0);
    for (size_t s = 0; s < nx; ++s) {
      const bool free = std::find(options.free_initial_states.begin(),
                                  options.free_initial_states.end(),
                                  info.states[s]) != options.free_initial_states.end();
      const double sigma = s < e.initial_state_sigma.size() ? e.initial_state_sigma[s] : NAN;
      if (!free && std::isfinite(sigma) && sigma > 0.0) variance[s] = sigma * sigma;
    }
    p->initial_variance_.push_back(variance);
  }
  for (size_t j = 0; j < ny; ++j) {
    scales.noise_level.push_back(power[j] > 0.0 ? std::sqrt(power[j] / count[j]) : NAN);
    if (count[j] > 0) scales.compared.push_back(static_cast<int>(j));
  }
  scales.sample_interval = intervals.empty() ? 1.0 : UpperMedian(intervals);
  if (!BuildDisturbanceLayout(options.disturbance, info, scales, &p->layout_, error)) return false;
  // log S + c >= 1 for every S above the floor (filter_error_cost.h).
  p->offsets_->c.assign(ny, 0.0);
  for (size_t j = 0; j < ny; ++j) p->offsets_->c[j] = 1.0 - std::log(p->layout_.outputs[j].floor);
  return true;
}

void OutputErrorProblem::AddInitialStatePriors(const InitialStatePrior& prior,
                                               OutputErrorProblem* p) {
  if (prior.apply == InitialStatePrior::Apply::kOff) return;
  auto applies = [&](const Experiment& e) {
    return prior.apply == InitialStatePrior::Apply::kAll || e.segment;
  };
  const size_t num_states = p->model_->info().states.size();
  for (size_t s = 0; s < num_states; ++s) {
    std::vector<Variable*> states;
    std::vector<double> guesses, magnitudes, sigmas;
    for (Variable& v : p->variables_) {
      if (v.kind != Variable::Kind::kInitialState || !v.free || v.index != static_cast<int>(s)) {
        continue;
      }
      const Experiment& e = p->experiments_[v.experiment];
      const double sigma = e.initial_state_sigma.size() > s ? e.initial_state_sigma[s] : NAN;
      if (!applies(e) || !(sigma > 0.0) || !std::isfinite(sigma)) continue;
      states.push_back(&v);
      guesses.push_back(e.initial_state_guess[s]);
      magnitudes.push_back(std::abs(e.initial_state_guess[s]));
      sigmas.push_back(sigma);
    }
    if (states.empty()) continue;
    const double median = UpperMedian(guesses);
    std::vector<double> deviations;
    for (double g : guesses) deviations.push_back(std::abs(g - median));
    const double reach =
        prior.bounds * std::max({1.4826 * UpperMedian(deviations),
                                 0.5 * *std::max_element(magnitudes.begin(), magnitudes.end()),
                                 10.0 * UpperMedian(sigmas)});
    for (size_t i = 0; i < states.size(); ++i) {
      Variable& v = *states[i];
      const Experiment& e = p->experiments_[v.experiment];
      const double guess = guesses[i];
      // Under the filter-error method the prior is a Gaussian one in the likelihood's own
      // units: r = (x0 - guess) / (scale sigma).
      static const double kUnit = 1.0;
      if (p->filter_error_) {
        p->problem_->AddResidualBlock(
            new PriorCost(&kUnit, 1.0 / (prior.scale * sigmas[i]), guess, v.scale), nullptr,
            v.block);
      } else if (e.prior_weight > 0.0) {
        p->problem_->AddResidualBlock(
            new PriorCost(&e.prior_weight, 1.0 / (prior.scale * sigmas[i]), guess, v.scale), nullptr,
            v.block);
      }
      if (reach > 0.0 && std::isfinite(reach)) {
        v.lower = std::max(v.lower, guess - reach);
        v.upper = std::min(v.upper, guess + reach);
        v.set_value(std::clamp(v.value(), v.lower, v.upper));
      }
    }
  }
}

void OutputErrorProblem::AddInputCorrectionPriors(OutputErrorProblem* p) {
  for (const Variable& v : p->variables_) {
    if (v.kind != Variable::Kind::kInputCorrection) continue;
    const Experiment& e = p->experiments_[v.experiment];
    // Without an output noise level (noise-free outputs) the prior still keeps each value
    // determined, at the weight of one sample.
    // The experiment's prior weight is read live (noise weights rescale it).
    static const double kUnit = 1.0;
    PriorCost* cost =
        e.prior_weight > 0.0
            ? new PriorCost(&e.prior_weight, 1.0 / v.scale, 0.0, v.scale)
            : new PriorCost(&kUnit, 1e-6 / std::sqrt(double(e.num_samples())) / v.scale, 0.0,
                            v.scale);
    p->problem_->AddResidualBlock(cost, nullptr, v.block);
  }
}

std::unique_ptr<OutputErrorProblem> OutputErrorProblem::Create(
    const ModelHandle* model, std::vector<Experiment> experiments,
    const std::vector<ParameterSpec>& parameters, const OutputErrorOptions& options,
    std::string* error) {
  const ModelInfo& info = model->info();
  std::unique_ptr<OutputErrorProblem> p(new OutputErrorProblem);
  p->model_ = model;
  p->specs_ = parameters;
  p->options_ = options;
  p->experiments_ = std::move(experiments);
  if (p->experiments_.empty()) {
    *error = "no experiments";
    return nullptr;
  }
  if (!MakeLoss(options, &p->loss_, error)) return nullptr;
  p->filter_error_ = options.disturbance.method == DisturbanceSpec::Method::kFilterError;
  if (p->filter_error_) {
    if (options.loss != "none") {
      *error = "a robust loss (" + options.loss +
               ") with the filter-error method: the likelihood is Gaussian; use loss none";
      return nullptr;
    }
    for (const Experiment& e : p->experiments_) {
      if (e.num_input_corrections() > 0) {
        *error = "experiment " + e.name +
                 ": input noise (input corrections) with the filter-error method; model the "
                 "input's noise as process noise instead";
        return nullptr;
      }
    }
  }

  // Specs by model parameter index; unnamed parameters fixed at their defaults.
  std::vector<ParameterSpec> specs(info.parameters.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    specs[i].name = info.parameters[i];
    specs[i].start = info.parameter_defaults[i];
    specs[i].role = ParameterRole::kFixed;
  }
  for (const ParameterSpec& spec : parameters) {
    int index = info.ParameterIndex(spec.name);
    if (index < 0) {
      *error = "unknown parameter '" + spec.name + "' (model " + info.name + " has " +
               JoinNames(info.parameters) + ")";
      return nullptr;
    }
    specs[index] = spec;
  }
  std::vector<bool> state_free(info.states.size(), false);
  for (const std::string& state : options.free_initial_states) {
    int index = info.StateIndex(state);
    if (index < 0) {
      *error = "unknown state '" + state + "' in free initial states (model " + info.name +
               " has " + JoinNames(info.states) + ")";
      return nullptr;
    }
    state_free[index] = true;
  }

  // One array holds every block, in variable order, never reallocated: Ceres orders blocks
  // by address in places (covariance), so addresses must follow the variables for results
  // to be reproducible from run to run and thread to thread.
  size_t corrections = 0;
  for (const Experiment& e : p->experiments_) corrections += e.num_input_corrections();
  if (p->filter_error_ && !BuildLayout(specs, options, p.get(), error)) return nullptr;
  p->storage_.reserve(specs.size() * (p->experiments_.size() + 1) +
                      info.states.size() * p->experiments_.size() + corrections +
                      p->layout_.parameters.size());
  auto add_variable = [&](Variable v, double start) {
    p->storage_.push_back(start / v.scale);
    v.block = &p->storage_.back();
    p->variables_.push_back(v);
    return static_cast<int>(p->variables_.size()) - 1;
  };
  const int num_experiments = static_cast<int>(p->experiments_.size());
  p->block_of_.assign(num_experiments, {});
  std::vector<int> shared(specs.size(), -1);
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].role == ParameterRole::kPerExperiment) continue;
    Variable v;
    v.name = specs[i].name;
    v.index = static_cast<int>(i);
    v.role = specs[i].role;
    v.scale = specs[i].EffectiveScale();
    v.lower = specs[i].lower;
    v.upper = specs[i].upper;
    v.free = IsEstimatedOnce(specs[i].role);
    shared[i] = add_variable(v, specs[i].start);
  }
  for (int e = 0; e < num_experiments; ++e) {
    const Experiment& experiment = p->experiments_[e];
    for (size_t i = 0; i < specs.size(); ++i) {
      if (shared[i] >= 0) {
        p->block_of_[e].push_back(shared[i]);
        continue;
      }
      Variable v;
      v.name = specs[i].name + "[" + experiment.name + "]";
      v.index = static_cast<int>(i);
      v.experiment = e;
      v.role = ParameterRole::kPerExperiment;
      v.scale = specs[i].EffectiveScale();
      v.lower = specs[i].lower;
      v.upper = specs[i].upper;
      double start = specs[i].start;
      const std::map<std::string, double>& carried = specs[i].experiment_starts;
      auto found = carried.find(experiment.name);
      if (found == carried.end()) found = carried.find(experiment.record);
      if (found != carried.end()) start = std::clamp(found->second, v.lower, v.upper);
      p->block_of_[e].push_back(add_variable(v, start));
    }
    for (size_t s = 0; s < info.states.size(); ++s) {
      Variable v;
      v.name = "x0." + info.states[s] + "[" + experiment.name + "]";
      v.kind = Variable::Kind::kInitialState;
      v.index = static_cast<int>(s);
      v.experiment = e;
      v.role = state_free[s] ? ParameterRole::kPerExperiment : ParameterRole::kFixed;
      v.free = state_free[s];
      const double start =
          state_free[s] ? experiment.initial_state_guess[s] : experiment.initial_state[s];
      p->block_of_[e].push_back(add_variable(v, start));
    }
    // Input corrections, free, starting at zero, block value c / sigma_c.
    for (const InputCorrectionGrid& g : experiment.input_corrections) {
      for (int j = 0; j < g.count; ++j) {
        Variable v;
        v.name = "c." + info.inputs[g.input] + "#" + std::to_string(j) + "[" + experiment.name + "]";
        v.kind = Variable::Kind::kInputCorrection;
        v.index = g.input;
        v.experiment = e;
        v.role = ParameterRole::kPerExperiment;
        v.scale = g.sigma > 0.0 ? g.sigma : 1.0;
        p->block_of_[e].push_back(add_variable(v, 0.0));
      }
    }
  }

  // The disturbance's parameters: shared, after every other variable.
  for (int k = 0; k < p->layout_.size(); ++k) {
    const NoiseParameter& noise = p->layout_.parameters[k];
    Variable v;
    v.index = k;
    v.name = noise.name;
    v.kind = Variable::Kind::kNoise;
    v.scale = noise.start;
    v.lower = noise.lower;
    v.upper = noise.upper;
    auto carried = options.noise_starts.find(noise.name);
    const double start = carried != options.noise_starts.end()
                             ? std::clamp(carried->second, noise.lower, noise.upper)
                             : noise.start;
    const int index = add_variable(v, start);
    for (int e = 0; e < num_experiments; ++e) p->block_of_[e].push_back(index);
  }

  p->problem_ = std::make_unique<ceres::Problem>();
  // Only Ceres' bounded trust region asks twice at one point on Jets (its projected line
  // search, evaluation_cache.h); without bounds a cache would hold Jacobians per experiment
  // to save only the stage's last Jacobian (its uncertainty analysis). (Bounds the
  // initial-state priors add below do not count: a missed copy, not a wrong one.)
  bool bounded = false;
  for (const Variable& v : p->variables_) {
    bounded |= v.free && (std::isfinite(v.lower) || std::isfinite(v.upper));
  }
  std::vector<double> scales(specs.size());
  for (size_t i = 0; i < specs.size(); ++i) scales[i] = specs[i].EffectiveScale();
  for (int e = 0; e < num_experiments; ++e) {
    std::vector<double*> blocks;
    for (int index : p->block_of_[e]) blocks.push_back(p->variables_[index].block);
    ExperimentCostOptions cost_options;
    cost_options.counts = p->counts_.get();
    if (options.evaluation_cache && bounded) {
      const int rows = (p->filter_error_ ? 2 : 1) * p->experiments_[e].num_samples();
      p->caches_.push_back(
          std::make_unique<EvaluationCache>(rows, static_cast<int>(blocks.size())));
      cost_options.cache = p->caches_.back().get();
    }
    ceres::CostFunction* cost =
        p->filter_error_
            ? model->NewFilterErrorCost(&p->experiments_[e], scales, &p->layout_,
                                        NoiseScales(p->layout_), p->initial_variance_[e],
                                        p->offsets_.get(), cost_options)
            : model->NewExperimentCost(&p->experiments_[e], scales, p->loss_.get(), cost_options);
    p->data_blocks_.push_back(p->problem_->AddResidualBlock(cost, nullptr, blocks));
  }
  AddInitialStatePriors(options.prior, p.get());
  AddInputCorrectionPriors(p.get());
  for (const Variable& v : p->variables_) {
    if (!v.free) {
      p->problem_->SetParameterBlockConstant(v.block);
      continue;
    }
    if (std::isfinite(v.lower)) p->problem_->SetParameterLowerBound(v.block, 0, v.lower / v.scale);
    if (std::isfinite(v.upper)) p->problem_->SetParameterUpperBound(v.block, 0, v.upper / v.scale);
  }
  return p;
}

std::unique_ptr<OutputErrorProblem> OutputErrorProblem::Clone() const {
  std::string error;
  std::unique_ptr<OutputErrorProblem> copy = Create(model_, experiments_, specs_, options_, &error);
  VESSELID_CHECK(copy != nullptr);  // the same inputs created this problem
  copy->SetValues(Values());
  return copy;
}

void OutputErrorProblem::SetChannelWeights(const std::vector<double>& weight) {
  for (Experiment& e : experiments_) vesselid::SetChannelWeights(weight, &e);
}

std::vector<std::vector<double>> OutputErrorProblem::ChannelWeights() const {
  std::vector<std::vector<double>> weights;
  for (const Experiment& e : experiments_) weights.push_back(e.channel_weight);
  return weights;
}

bool OutputErrorProblem::CostWithChannelWeights(const std::vector<std::vector<double>>& weights,
                                                double* cost) {
  if (weights.size() != experiments_.size()) return false;
  const std::vector<std::vector<double>> current = ChannelWeights();
  for (size_t e = 0; e < experiments_.size(); ++e) {
    vesselid::SetChannelWeights(weights[e], &experiments_[e]);
  }
  const bool ok = Cost(cost);
  for (size_t e = 0; e < experiments_.size(); ++e) {
    vesselid::SetChannelWeights(current[e], &experiments_[e]);
  }
  return ok;
}

int OutputErrorProblem::num_samples() const {
  int total = 0;
  for (const Experiment& e : experiments_) total += e.num_samples();
  return total;
}

int OutputErrorProblem::num_residuals() const {
  return filter_error_ ? 2 * num_samples() : num_samples();
}

std::vector<double> OutputErrorProblem::NoiseValues() const {
  std::vector<double> values;
  for (const Variable& v : variables_) {
    if (v.kind == Variable::Kind::kNoise) values.push_back(v.value());
  }
  return values;
}

bool OutputErrorProblem::RunFilter(int e, int steps, FilterRun* run) const {
  if (!filter_error_) return false;
  const std::vector<double> p = ParametersOf(e), x0 = InitialStateOf(e), theta = NoiseValues();
  return model_->FilterInnovations(experiments_[e], p.data(), x0.data(),
                                   initial_variance_[e].data(), layout_, theta.data(), steps, run);
}

std::vector<double> OutputErrorProblem::OperatingRange() const {
  const int nx = static_cast<int>(model_->info().states.size());
  std::vector<double> range =
      EmptyOperatingRange(nx, static_cast<int>(model_->info().inputs.size()));
  for (size_t e = 0; e < experiments_.size(); ++e) {
    const int index = static_cast<int>(e);
    model_->StateLimits(experiments_[e], ParametersOf(index).data(),
                        InitialStateOf(index).data(), range.data());
    AddInputRange(experiments_[e], nx, &range);
  }
  return range;
}

bool OutputErrorProblem::ScoreOmittedTerms(int e, const std::vector<OmittedTerm>& terms,
                                           OmittedTermScore* score,
                                           std::vector<std::string>* free) const {
  if (!filter_error_) return false;
  const int np = static_cast<int>(model_->info().parameters.size());
  const int nx = static_cast<int>(model_->info().states.size());
  std::vector<int> directions;
  free->clear();
  for (int j = 0; j < np + nx; ++j) {
    const Variable& v = variables_[block_of_[e][j]];
    if (!v.free) continue;
    directions.push_back(j);
    free->push_back(v.name);
  }
  for (const Variable& v : variables_) {
    if (v.kind != Variable::Kind::kNoise || !v.free) continue;
    directions.push_back(np + nx + v.index);
    free->push_back(v.name);
  }
  for (size_t j = 0; j < terms.size(); ++j) {
    directions.push_back(np + nx + layout_.size() + static_cast<int>(j));
  }
  const std::vector<double> p = ParametersOf(e), x0 = InitialStateOf(e), theta = NoiseValues();
  return model_->ScoreOmittedTerms(experiments_[e], p.data(), x0.data(),
                                   initial_variance_[e].data(), layout_, theta.data(), terms,
                                   directions, score);
}

double OutputErrorProblem::NegativeLogLikelihood() const {
  if (!filter_error_) return std::numeric_limits<double>::quiet_NaN();
  double total = 0.0;
  for (size_t e = 0; e < experiments_.size(); ++e) {
    FilterRun run;
    if (!RunFilter(static_cast<int>(e), 0, &run)) return std::numeric_limits<double>::quiet_NaN();
    total += run.negative_log_likelihood;
  }
  return total;
}

void OutputErrorProblem::ScanNoiseStarts() {
  if (!filter_error_) return;
  for (const Variable& v : variables_) {
    if (v.kind != Variable::Kind::kNoise || !v.free) continue;
    // A time constant or frequency is scanned over a narrower range than a variance scale.
    const NoiseParameter::Kind kind = layout_.parameters[v.index].kind;
    if (kind == NoiseParameter::Kind::kWaveZeta) continue;
    const double start = v.value();
    double best = start, best_nll = NegativeLogLikelihood();
    for (double factor : {1e-4, 1e-3, 1e-2, 1e-1, 10.0, 100.0}) {
      const bool narrow = kind == NoiseParameter::Kind::kAr1Tau ||
                          kind == NoiseParameter::Kind::kWaveOmega;
      if (narrow && (factor < 0.01 || factor > 10.0)) continue;
      const double value = start * factor;
      if (value < v.lower || value > v.upper) continue;
      v.set_value(value);
      const double nll = NegativeLogLikelihood();
      if (nll < best_nll) {
        best_nll = nll;
        best = value;
      }
    }
    v.set_value(best);
  }
}

std::vector<double> OutputErrorProblem::LowestLogVariances() const {
  std::vector<double> lowest(offsets_->c.size(), std::numeric_limits<double>::infinity());
  for (size_t e = 0; e < experiments_.size(); ++e) {
    FilterRun run;
    if (!RunFilter(static_cast<int>(e), 0, &run)) return {};
    for (int i = 0; i < experiments_[e].num_samples(); ++i) {
      const int j = experiments_[e].samples[i].output;
      lowest[j] = std::min(lowest[j], std::log(run.variance[i]));
    }
  }
  return lowest;
}

std::vector<double> OutputErrorProblem::CentreLikelihood(double margin) {
  std::vector<double> solve = offsets_->c;
  if (!filter_error_) return solve;
  const std::vector<double> lowest = LowestLogVariances();
  for (size_t j = 0; j < lowest.size(); ++j) {
    if (std::isfinite(lowest[j])) offsets_->c[j] = 1.0 + margin - lowest[j];
  }
  ++offsets_->revision;
  return solve;
}

double OutputErrorProblem::LowestLikelihoodTerm() const {
  if (!filter_error_) return NAN;
  const std::vector<double> lowest = LowestLogVariances();
  if (lowest.empty()) return NAN;
  double term = std::numeric_limits<double>::infinity();
  for (size_t j = 0; j < lowest.size(); ++j) {
    if (std::isfinite(lowest[j])) term = std::min(term, lowest[j] + offsets_->c[j]);
  }
  return term;
}

int OutputErrorProblem::num_free() const {
  return static_cast<int>(std::count_if(variables_.begin(), variables_.end(),
                                        [](const Variable& v) { return v.free; }));
}

std::vector<double> OutputErrorProblem::ParametersOf(int e) const {
  std::vector<double> values;
  const size_t n = model_->info().parameters.size();
  for (size_t j = 0; j < n; ++j) values.push_back(variables_[block_of_[e][j]].value());
  return values;
}

std::vector<double> OutputErrorProblem::InitialStateOf(int e) const {
  std::vector<double> values;
  const size_t n = model_->info().parameters.size();
  for (size_t j = n; j < n + model_->info().states.size(); ++j)
    values.push_back(variables_[block_of_[e][j]].value());
  return values;
}

std::vector<double> OutputErrorProblem::InputCorrectionsOf(int e) const {
  std::vector<double> values;
  const size_t first = model_->info().parameters.size() + model_->info().states.size();
  const size_t last = first + experiments_[e].num_input_corrections();
  for (size_t j = first; j < last; ++j)
    values.push_back(variables_[block_of_[e][j]].value());
  return values;
}

std::vector<double> OutputErrorProblem::Values() const {
  std::vector<double> values;
  for (const Variable& v : variables_) values.push_back(v.value());
  return values;
}

void OutputErrorProblem::SetValues(const std::vector<double>& values) {
  for (size_t i = 0; i < variables_.size(); ++i) variables_[i].set_value(values[i]);
}

void OutputErrorProblem::ReleaseEvaluationCaches() {
  for (const std::unique_ptr<EvaluationCache>& cache : caches_) cache->Clear();
}

bool OutputErrorProblem::Cost(double* cost) {
  ceres::Problem::EvaluateOptions options;
  return problem_->Evaluate(options, cost, nullptr, nullptr, nullptr);
}

}  // namespace vesselid
