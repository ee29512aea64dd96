#include "engine/run/prediction_band.h"

#include <cmath>
#include <map>

#include "Eigen/Dense"
#include "engine/base/parallel_for.h"
#include "engine/solve/solution_jacobian.h"

namespace vesselid {
namespace {

// A column of S: a free variable of the run's problem, and the variance of its value.
struct Column {
  int variable = -1;
  double variance = 0.0;
};

// Per output name, the training fit's mean square residual and its noise level (pooled over
// the runs of the last accepted output-error stage, the stage whose estimates make the final
// values).
struct TrainingLevel {
  double mean_square = 0.0;
  double noise = std::nan("");
};

std::map<std::string, TrainingLevel> TrainingLevels(const RunResult& run) {
  std::map<std::string, double> sum, count, noise_sum, noise_count;
  for (auto s = run.stages.rbegin(); s != run.stages.rend(); ++s) {
    if (!s->rejected.empty() || s->summary.fits.empty()) continue;
    for (const ExperimentFit& fit : s->summary.fits) {
      if (fit.diverged) continue;
      for (const ChannelMetrics& m : fit.channels) {
        sum[m.output] += m.rmse * m.rmse * m.samples;
        count[m.output] += m.samples;
        if (std::isfinite(m.noise) && m.noise > 0.0) {
          noise_sum[m.output] += m.noise * m.noise * m.samples;
          noise_count[m.output] += m.samples;
        }
      }
    }
    break;
  }
  std::map<std::string, TrainingLevel> levels;
  for (const auto& [output, total] : sum) {
    if (!(count[output] > 0 && total > 0.0)) continue;
    TrainingLevel& level = levels[output];
    level.mean_square = total / count[output];
    if (noise_count[output] > 0) level.noise = std::sqrt(noise_sum[output] / noise_count[output]);
  }
  return levels;
}

// sigma_o^2 of each output index of `info` for a held-out run: the training fit's mean square,
// raised by the run's own noise level where that is higher than the training runs' (a noisier
// record is not a structure the model misses); 0 where the training fit has no such output.
std::vector<double> RunVariances(const ModelInfo& info, const ExperimentFit& fit,
                                 const std::map<std::string, TrainingLevel>& levels) {
  std::vector<double> variance(info.outputs.size(), 0.0);
  for (size_t o = 0; o < info.outputs.size(); ++o) {
    auto found = levels.find(info.outputs[o]);
    if (found == levels.end()) continue;
    variance[o] = found->second.mean_square;
    for (const ChannelMetrics& m : fit.channels) {
      if (m.output == info.outputs[o] && m.noise > found->second.noise) {
        variance[o] *= (m.noise * m.noise) / (found->second.noise * found->second.noise);
      }
    }
  }
  return variance;
}

// Covariance of the final values of the estimated shared parameters (model order), from
// their standard errors and the correlations of the last accepted stage that has the pair.
Eigen::MatrixXd SharedCovariance(const RunResult& run, std::vector<int>* estimated) {
  estimated->clear();
  std::vector<double> se;
  for (size_t i = 0; i < run.parameters.size(); ++i) {
    const FinalParameter& p = run.parameters[i];
    if (!IsEstimatedOnce(p.role) || !(std::isfinite(p.std_error) && p.std_error > 0.0)) continue;
    estimated->push_back(static_cast<int>(i));
    se.push_back(p.std_error);
  }
  const int n = static_cast<int>(estimated->size());
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < n; ++a) covariance(a, a) = se[a] * se[a];
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const std::string& na = run.parameters[(*estimated)[a]].name;
      const std::string& nb = run.parameters[(*estimated)[b]].name;
      for (auto s = run.stages.rbegin(); s != run.stages.rend(); ++s) {
        if (!s->rejected.empty()) continue;
        int ia = -1, ib = -1;
        for (size_t k = 0; k < s->correlation_names.size(); ++k) {
          if (s->correlation_names[k] == na) ia = static_cast<int>(k);
          if (s->correlation_names[k] == nb) ib = static_cast<int>(k);
        }
        if (ia < 0 || ib < 0) continue;
        const double c = s->correlation(ia, ib);
        if (std::isfinite(c)) covariance(a, b) = covariance(b, a) = c * se[a] * se[b];
        break;
      }
    }
  }
  return covariance;
}

// The standard error of run `experiment`'s own value of `parameter` (its burn-in estimate,
// weighed with the training runs'); NaN if none.
double OwnStdError(const HeldOutParameters& own, const std::string& parameter,
                   const std::string& experiment) {
  for (const Estimate& e : own.estimates) {
    if (e.name == parameter && e.experiment == experiment) return e.std_error;
  }
  return std::nan("");
}

// The band of one run: `experiment` flown from fit.start's state and values.
PredictionBand BandOf(const ModelHandle& model, Experiment experiment, const ExperimentFit& fit,
                      const RunResult& run, const std::vector<int>& shared,
                      const Eigen::MatrixXd& shared_covariance,
                      const std::map<std::string, TrainingLevel>& levels) {
  PredictionBand band;
  const ModelInfo& info = model.info();
  const std::vector<double> variance = RunVariances(info, fit, levels);
  const std::vector<double>& values = fit.start.values;
  const std::vector<double>& x0 = fit.start.initial_state;
  if (values.size() != info.parameters.size() || x0.size() != info.states.size()) return band;
  // Every parameter fixed at the run's values but the estimated ones, free at theirs; a run's
  // own parameters free as per-experiment; every initial state free at the flown start.
  std::vector<ParameterSpec> specs;
  for (size_t i = 0; i < values.size(); ++i) {
    ParameterSpec spec;
    spec.name = info.parameters[i];
    spec.start = values[i];
    spec.role = ParameterRole::kFixed;
    for (int k : shared) {
      if (run.parameters[k].name == spec.name) spec.role = ParameterRole::kFree;
    }
    for (const std::string& own : run.final_held_out_parameters.parameters) {
      if (own == spec.name) spec.role = ParameterRole::kPerExperiment;
    }
    specs.push_back(spec);
  }
  experiment.initial_state = x0;
  experiment.initial_state_guess = x0;
  OutputErrorOptions options;
  options.free_initial_states = info.states;
  options.prior.apply = InitialStatePrior::Apply::kOff;
  options.evaluation_cache = false;
  std::string error;
  std::vector<Experiment> one{experiment};
  std::unique_ptr<OutputErrorProblem> problem =
      OutputErrorProblem::Create(&model, std::move(one), specs, options, &error);
  if (problem == nullptr) return band;
  SolutionJacobian solution;
  if (!EvaluateSolutionJacobian(problem.get(), 1, &solution)) return band;

  // Columns and their variances.
  const Experiment& e = problem->experiments().front();
  std::vector<Column> columns;
  std::vector<int> shared_column;  // column of each shared estimate, in `shared` order
  for (size_t c = 0; c < solution.variables.size(); ++c) {
    const Variable& v = problem->variables()[solution.variables[c]];
    Column column;
    column.variable = static_cast<int>(c);
    if (v.kind == Variable::Kind::kParameter && v.role != ParameterRole::kPerExperiment) {
      shared_column.push_back(static_cast<int>(columns.size()));
      columns.push_back(column);
      continue;
    }
    if (v.kind == Variable::Kind::kParameter) {
      column.variance = std::pow(OwnStdError(run.final_held_out_parameters,
                                             info.parameters[v.index], e.name), 2);
    } else if (v.kind == Variable::Kind::kInitialState) {
      const int o = info.OutputIndex(info.states[v.index]);
      double sd = e.initial_state_sigma.size() > static_cast<size_t>(v.index)
                      ? e.initial_state_sigma[v.index]
                      : std::nan("");
      const double noise = o >= 0 ? e.NoiseLevel(o) : std::nan("");
      if (std::isfinite(noise)) sd = std::isfinite(sd) ? std::max(sd, noise) : noise;
      column.variance = std::isfinite(sd) ? sd * sd : 0.0;
    }
    if (std::isfinite(column.variance) && column.variance > 0.0) columns.push_back(column);
  }
  const int n = static_cast<int>(columns.size());
  std::vector<int> column_of(solution.variables.size(), -1);  // Jacobian column -> S's
  for (int m = 0; m < n; ++m) column_of[columns[m].variable] = m;
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < n; ++c) covariance(c, c) = columns[c].variance;
  if (static_cast<int>(shared_column.size()) == shared_covariance.rows()) {
    for (size_t a = 0; a < shared_column.size(); ++a) {
      for (size_t b = 0; b < shared_column.size(); ++b)
        covariance(shared_column[a], shared_column[b]) = shared_covariance(a, b);
    }
  }
  // P = L L' with L = V sqrt(max(lambda, 0)): a singular P (a correlation of 1) is no harm.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  const Eigen::MatrixXd root =
      eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();

  // Scored samples: physical residual r_i = residual / w and sensitivity row s_i (per unit
  // of each value: the Jacobian is per unit of value / scale).
  const double scored_from = e.node_time.front() + fit.start.burn_in;
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(n);
  double q0 = 0.0;
  std::map<int, std::pair<double, int>> per_output;  // sum r^2 / sigma^2, samples
  Eigen::VectorXd s(n);
  for (int k = 0; k + 1 < static_cast<int>(e.node_first_sample.size()); ++k) {
    if (e.node_time[k] <= scored_from && fit.start.burn_in > 0.0) continue;
    for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
      const ExperimentSample& sample = e.samples[i];
      if (sample.weight == 0.0) continue;
      if (!(variance[sample.output] > 0.0)) continue;
      const double sigma = std::sqrt(variance[sample.output]);
      const double r = solution.residuals[i] / sample.weight / sigma;
      s.setZero();
      for (int j = solution.jacobian.rows[i]; j < solution.jacobian.rows[i + 1]; ++j) {
        const int c = solution.jacobian.cols[j];
        if (column_of[c] < 0) continue;
        const Variable& v = problem->variables()[solution.variables[c]];
        s(column_of[c]) = solution.jacobian.values[j] / (sample.weight * v.scale * sigma);
      }
      normal.selfadjointView<Eigen::Lower>().rankUpdate(s);
      gradient += s * r;
      q0 += r * r;
      per_output[sample.output].first += r * r;
      per_output[sample.output].second += 1;
      ++band.samples;
    }
  }
  if (band.samples == 0) return band;
  const Eigen::MatrixXd full = normal.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) + root.transpose() * full * root;
  const Eigen::VectorXd b = root.transpose() * gradient;
  const double explained = b.dot(a.ldlt().solve(b));
  band.done = true;
  band.ratio = std::max(0.0, q0 - explained) / band.samples;
  band.raw_ratio = q0 / band.samples;
  for (const auto& [o, sum] : per_output) {
    band.outputs.push_back(info.outputs[o]);
    band.output_ratio.push_back(sum.first / std::max(1, sum.second));
  }
  return band;
}

}  // namespace

bool SetPredictionBands(const RunConfig& config, const ModelHandle& model,
                        const std::vector<std::string>& records, const ExperimentOptions& options,
                        TrajectoryCache* cache, RunResult* run, std::string* error) {
  std::vector<std::string> names;  // the runs (a record's segments are runs of their own)
  std::vector<int> fits;
  for (size_t k = 0; k < run->final_validation.size(); ++k) {
    const ExperimentFit& fit = run->final_validation[k];
    if (fit.diverged || fit.start.initial_state.empty() ||
        fit.start.mode != HeldOutStartModeToString(HeldOutStart::Mode::kMeasured)) {
      continue;
    }
    names.push_back(fit.experiment);
    fits.push_back(static_cast<int>(k));
  }
  const std::map<std::string, TrainingLevel> levels = TrainingLevels(*run);
  if (names.empty() || levels.empty()) return true;
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, records, model, options, cache, &experiments, error)) return false;
  std::vector<int> shared;
  const Eigen::MatrixXd covariance = SharedCovariance(*run, &shared);
  const int count = static_cast<int>(fits.size());
  std::vector<PredictionBand> bands(count);
  ParallelFor(count, 0, [&](int i) {
    for (const Experiment& e : experiments) {
      if (e.name != names[i]) continue;
      bands[i] = BandOf(model, e, run->final_validation[fits[i]], *run, shared, covariance,
                        levels);
    }
  });
  for (int i = 0; i < count; ++i) run->final_validation[fits[i]].band = std::move(bands[i]);
  return true;
}

}  // namespace vesselid
