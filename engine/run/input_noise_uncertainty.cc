#include "engine/run/input_noise_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>

#include "engine/base/case_seed.h"
#include "engine/base/chi_square.h"
#include "engine/base/parallel_for.h"
#include "engine/data/white_noise.h"
#include "engine/run/estimate_specs.h"
#include "engine/run/experiment_residuals.h"
#include "engine/solve/covariance.h"
#include "engine/solve/uncertainty_method.h"

namespace vesselid {
namespace {

struct NoisyInput {
  int experiment = 0;
  int input = 0;        // model input index
  double sigma = 0.0;   // model units
  std::string name;     // the model input's name
  std::string text;     // "delta on train (0.15 deg)"
};

std::vector<NoisyInput> NoisyInputs(const RunConfig& config, TrajectoryCache* cache,
                                    const OutputErrorProblem& problem) {
  const ModelInfo& info = problem.model().info();
  std::vector<NoisyInput> noisy;
  std::map<std::pair<std::string, std::string>, double> tested;  // (record, column): SD
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& x = problem.experiments()[e];
    const ExperimentSpec* spec = config.FindExperiment(x.record.empty() ? x.name : x.record);
    if (spec == nullptr) continue;
    for (const auto& [input, column] : spec->inputs) {
      const int j = info.InputIndex(input);
      if (j < 0 || spec->input_noise.count(input) > 0) continue;
      // Segments and windows of one record share its test.
      const auto key = std::make_pair(spec->name, column);
      auto found = tested.find(key);
      if (found == tested.end()) {
        std::vector<double> values;
        const double sd = WindowSamples(*spec, column, cache, &values) ? WhiteInputNoise(values)
                                                                       : 0.0;
        found = tested.emplace(key, sd).first;
      }
      const double sigma = found->second;
      if (!(sigma > 0.0)) continue;
      const bool degrees = spec->IsDegreeColumn(column);
      NoisyInput n;
      n.experiment = static_cast<int>(e);
      n.input = j;
      n.sigma = sigma;  // WindowSamples reads a degree column in radians
      n.name = input;
      char text[160];
      std::snprintf(text, sizeof(text), "%s on %s (%.3g %s)", input.c_str(), x.name.c_str(),
                    degrees ? sigma * 180.0 / M_PI : sigma,
                    degrees ? "deg" : info.InputUnit(j).c_str());
      n.text = text;
      noisy.push_back(std::move(n));
    }
  }
  return noisy;
}

// Adds white noise of n.sigma, drawn at the nodes and linear between them, to input n.input's
// rows of the input cache (each step's start, midpoint and end, and the last node).
void AddNodeNoise(const NoisyInput& n, std::mt19937_64* rng, Experiment* x) {
  const int nodes = x->num_nodes(), nu = x->num_inputs, j = n.input;
  int steps = 0;
  for (int m : x->node_substeps) steps += m;
  if (nodes < 2 || x->input_cache.size() != static_cast<size_t>(3 * steps + 1) * nu) return;
  std::normal_distribution<double> noise(0.0, n.sigma);
  std::vector<double> at(nodes);
  for (double& v : at) v = noise(*rng);
  int step = 0;
  for (int k = 0; k + 1 < nodes; ++k) {
    const int m = x->node_substeps[k];
    const auto value = [&](double f) { return at[k] + f * (at[k + 1] - at[k]); };
    for (int i = 0; i < m; ++i, ++step) {
      const double a = static_cast<double>(i) / m, b = static_cast<double>(i + 1) / m;
      x->input_cache[(3 * step) * nu + j] += value(a);
      x->input_cache[(3 * step + 1) * nu + j] += value(0.5 * (a + b));
      x->input_cache[(3 * step + 2) * nu + j] += value(b);
    }
  }
  x->input_cache[(3 * step) * nu + j] += at.back();
}

// Mean square per output of d_i - reference_i over experiment e's samples, d the residuals
// (simulated - measured) at the problem's values; reference empty: of d itself. NaN where an
// output has none.
std::vector<double> OutputMeanSquares(OutputErrorProblem* problem, int e, int outputs,
                                      const std::vector<double>& reference,
                                      std::vector<double>* d) {
  std::vector<double> sum(outputs, 0.0), ms(outputs, std::nan(""));
  std::vector<int> count(outputs, 0);
  if (!SimulatedMinusMeasured(problem, e, d)) return ms;
  const Experiment& x = problem->experiments()[e];
  for (size_t i = 0; i < d->size(); ++i) {
    const double v = reference.empty() ? (*d)[i] : (*d)[i] - reference[i];
    if (!std::isfinite(v)) continue;
    sum[x.samples[i].output] += v * v;
    ++count[x.samples[i].output];
  }
  for (int o = 0; o < outputs; ++o) {
    if (count[o] > 0) ms[o] = sum[o] / count[o];
  }
  return ms;
}

// The 99 % quantile of a mean square's distribution from draws c_r of it: scaled chi-square
// with the draws' mean m and k = 2 m^2 / var degrees of freedom (Satterthwaite). A random
// walk's power over one record has few degrees of freedom: the record's own realisation may
// lie far above the refits' mean.
double UpperQuantile99(const std::vector<double>& c) {
  double m = 0.0, v = 0.0;
  for (double x : c) m += x;
  m /= c.size();
  for (double x : c) v += (x - m) * (x - m);
  v /= std::max<size_t>(1, c.size() - 1);
  if (!(m > 0.0)) return 0.0;
  const double k = v > 0.0 ? std::clamp(2.0 * m * m / v, 0.5, 1e6) : 1e6;
  double lo = 0.0, hi = k + 50.0 * std::sqrt(2.0 * k) + 50.0;
  for (int i = 0; i < 100; ++i) {  // P(chi2_k > q) = 0.01 by bisection
    const double q = 0.5 * (lo + hi);
    (ChiSquareUpperTail(q, k) > 0.01 ? lo : hi) = q;
  }
  return m * 0.5 * (lo + hi) / k;
}

}  // namespace

void AddInputNoiseSpread(const RunConfig& config, TrajectoryCache* cache,
                         const StageOptions& options, const OutputErrorOptions& problem_options,
                         OutputErrorProblem* solved, StageSummary* summary) {
  Uncertainty& u = summary->uncertainty;
  if (!options.compute_uncertainty || !options.uncertainty.input_noise || !u.available) return;
  // A bootstrap's replicates and a configured HAC see the input noise's residuals themselves.
  if (IsBootstrap(options.uncertainty.method) ||
      options.uncertainty.method == UncertaintyMethod::kSandwichHac) {
    return;
  }
  const std::vector<NoisyInput> noisy = NoisyInputs(config, cache, *solved);
  if (noisy.empty()) return;
  double samples = 0.0;
  for (const Experiment& x : solved->experiments()) samples += x.num_samples();
  if (solved->experiments().size() > static_cast<size_t>(kMaxInputNoiseExperiments) ||
      samples > kMaxInputNoiseSamples) {
    char note[256];
    std::snprintf(note, sizeof(note),
                  "input noise: %zu experiments/segments and %.3g samples are too many for the "
                  "refits (at most %d and %.0g); the standard errors leave out the noise on %s",
                  solved->experiments().size(), samples, kMaxInputNoiseExperiments,
                  kMaxInputNoiseSamples, noisy.front().text.c_str());
    summary->notes.push_back(note);
    return;
  }
  const int runs = options.uncertainty.input_noise_runs;
  const unsigned seed = options.uncertainty.bootstrap.seed;
  const std::vector<ParameterSpec> specs = EstimateSpecs(*solved);
  const int count = static_cast<int>(solved->experiments().size());
  const int outputs = static_cast<int>(solved->model().info().outputs.size());
  std::vector<std::vector<double>> base(count), base_residuals(count);
  for (int e = 0; e < count; ++e) {
    base[e] = OutputMeanSquares(solved, e, outputs, {}, &base_residuals[e]);
  }

  StageOptions replicate_options = ReplicateOptions(options);
  // From the optimum the first steps are the Gauss-Newton moves A e' the spread is about.
  replicate_options.local.max_iterations = kInputNoiseIterations;
  std::vector<std::vector<double>> values(runs);
  std::vector<std::vector<std::vector<double>>> squares(runs);
  ParallelFor(runs, options.uncertainty.bootstrap.num_threads, [&](int r) {
    std::vector<Experiment> experiments = solved->experiments();
    for (const NoisyInput& n : noisy) {
      std::mt19937_64 rng(CaseSeed(seed, 1000 + n.experiment * 64 + n.input, r));
      AddNodeNoise(n, &rng, &experiments[n.experiment]);
    }
    std::unique_ptr<OutputErrorProblem> p = SolveReplicate(
        *solved, std::move(experiments), specs, problem_options, replicate_options);
    if (p == nullptr) return;
    // The simulated outputs' move from the stage's (the replicate's residuals minus the
    // stage's): the input noise's part of a residual once the refit has absorbed what it can.
    std::vector<double> d;
    for (int e = 0; e < count; ++e) {
      squares[r].push_back(OutputMeanSquares(p.get(), e, outputs, base_residuals[e], &d));
    }
    values[r] = p->Values();
  });
  std::vector<int> good;
  for (int r = 0; r < runs; ++r) {
    if (!values[r].empty()) good.push_back(r);
  }
  // The noisy inputs named in the notes: the first few (a segmented record repeats its own).
  constexpr size_t kNamedInputs = 4;
  std::string inputs;
  for (size_t i = 0; i < noisy.size() && i < kNamedInputs; ++i) {
    inputs += (i == 0 ? "" : ", ") + noisy[i].text;
  }
  if (noisy.size() > kNamedInputs) {
    inputs += " and " + std::to_string(noisy.size() - kNamedInputs) + " more";
  }
  char text[512];
  if (good.size() < std::max<size_t>(2, std::ceil(kMinInputNoiseSolved * runs))) {
    std::snprintf(text, sizeof(text),
                  "input noise: only %zu of %d refits with the measured inputs' noise added "
                  "again solved; the standard errors leave out the noise on %s",
                  good.size(), runs, inputs.c_str());
    summary->notes.push_back(text);
    return;
  }
  // Cov_input over every free variable (the stage's matrix and its per-experiment blocks).
  const auto covariance = [&](int a, int b) {
    double ma = 0.0, mb = 0.0;
    for (int r : good) ma += values[r][a], mb += values[r][b];
    ma /= good.size();
    mb /= good.size();
    double sum = 0.0;
    for (int r : good) sum += (values[r][a] - ma) * (values[r][b] - mb);
    return sum / (good.size() - 1);
  };
  // The base the input noise's part is added to: the Hessian's covariance (output noise).
  // Where `auto` chose the HAC for coloured residuals, the colour may be the input noise's own,
  // which the HAC already counts: the Hessian plus the refits' spread is reported unless the
  // HAC is wider still (colour beyond the input noise's).
  const int n = static_cast<int>(u.variables.size());
  const bool from_hac = u.method == "sandwich_hac";
  Uncertainty total = u;
  if (from_hac) {
    Uncertainty hessian;
    if (!ComputeUncertainty(solved, summary->local().final_cost, &hessian) ||
        hessian.variables != u.variables || hessian.covariance.rows() != n) {
      summary->notes.push_back("input noise: the Hessian's covariance could not be formed; the "
                               "HAC's standard errors are kept");
      return;
    }
    total = std::move(hessian);
    total.hessian_std_errors = total.std_errors;
    total.method = "hessian";
  } else if (u.hessian_std_errors.empty()) {
    total.hessian_std_errors = u.std_errors;
  }
  if (total.covariance.rows() == n) {
    // Each variance grows by the refits' (var_i), the correlations stay the Hessian's: C_ab
    // s_a s_b with s_i = sqrt(1 + var_i / C_ii). A dozen refits estimate a variance to about
    // +-40 %, a correlation far worse (a 0.99 ridge came out 0.79 added whole).
    std::vector<double> scale(n, 1.0);
    for (int a = 0; a < n; ++a) {
      const double c = total.covariance(a, a);
      const double v = covariance(total.variables[a], total.variables[a]);
      if (c > 0.0 && std::isfinite(v)) scale[a] = std::sqrt(1.0 + v / c);
    }
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) total.covariance(a, b) *= scale[a] * scale[b];
    }
    SetStdErrorsAndCorrelation(&total);
  }
  for (size_t i = 0; i < total.block_variables.size(); ++i) {
    const double se = total.block_std_errors[i];
    total.block_std_errors[i] =
        std::sqrt(se * se + covariance(total.block_variables[i], total.block_variables[i]));
  }
  // The HAC wider than the sum (geometric mean of the ratios above 1): kept.
  double log_ratio = 0.0;
  int ratios = 0;
  for (int i = 0; from_hac && i < n; ++i) {
    const double r = u.std_errors[i] / total.std_errors[i];
    if (std::isfinite(r) && r > 0.0) log_ratio += std::log(r), ++ratios;
  }
  const bool hac_kept = ratios > 0 && log_ratio / ratios > 0.0;
  if (!hac_kept) {
    total.method_reason =
        from_hac ? "auto: the Hessian's covariance with the input noise's part below (the HAC, "
                   "which the noise's colour chose, would count it again, and is narrower)"
                 : u.method_reason;
    u = std::move(total);
  }
  u.input_noise_runs = runs;
  u.input_noise_failed = runs - static_cast<int>(good.size());
  u.input_noise_std_errors.clear();
  for (int index : u.variables) u.input_noise_std_errors.push_back(std::sqrt(covariance(index, index)));
  u.input_noise_inputs.clear();
  for (const NoisyInput& x : noisy) {
    u.input_noise_inputs.push_back(solved->experiments()[x.experiment].name + ":" + x.name);
  }
  // The share of each experiment's residual power that the input noise makes.
  const std::vector<std::string>& names = solved->model().info().outputs;
  u.input_noise_share.clear();
  for (int e = 0; e < count; ++e) {
    for (int o = 0; o < outputs; ++o) {
      if (!(base[e][o] > 0.0)) continue;
      std::vector<double> c;
      for (int r : good) c.push_back(squares[r][e][o]);
      u.input_noise_share[solved->experiments()[e].name][names[o]] =
          std::clamp(UpperQuantile99(c) / base[e][o], 0.0, 1.0);
    }
  }
  if (hac_kept) {
    std::snprintf(text, sizeof(text),
                  "; wider than the Hessian's with the spread of %zu refits with the measured "
                  "inputs' white noise added again (%s): the residuals' colour is more than "
                  "the input noise's",
                  good.size(), inputs.c_str());
  } else {
    std::snprintf(text, sizeof(text),
                  "; plus the spread of %zu refits with the measured inputs' white noise added "
                  "again (errors in variables: %s)",
                  good.size(), inputs.c_str());
  }
  u.method_reason += text;
  std::snprintf(text, sizeof(text),
                "input noise: the standard errors include the noise on %s, measured by %zu "
                "refits with it added again (%d failed)%s",
                inputs.c_str(), good.size(), runs - static_cast<int>(good.size()),
                hac_kept ? "; the HAC's, wider, are reported" : "");
  summary->notes.push_back(text);
}

}  // namespace vesselid
