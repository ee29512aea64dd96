#include "engine/run/bootstrap_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>

#include "engine/base/case_seed.h"
#include "engine/base/nan.h"
#include "engine/base/parallel_for.h"
#include "engine/run/estimate_specs.h"
#include "engine/run/experiment_residuals.h"

namespace vesselid {
namespace {

// d of each output at every node: its value at the node, else at the nearest earlier node
// sampling it (else the first later one), so that a block drawn from any node has every
// channel (channels at different rates).
std::vector<std::vector<double>> NodeFilled(const Experiment& e, const std::vector<double>& d) {
  const int outputs = static_cast<int>(e.output_sample_count.size());
  std::vector<std::vector<double>> filled(outputs, std::vector<double>(e.num_nodes(), kNaN));
  for (int k = 0; k < e.num_nodes(); ++k) {
    for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
      if (std::isfinite(d[i])) filled[e.samples[i].output][k] = d[i];
    }
  }
  for (std::vector<double>& f : filled) {
    double last = kNaN;
    for (double& v : f) std::isfinite(v) ? (last = v) : (v = last);
    for (auto v = f.rbegin(); v != f.rend(); ++v) std::isfinite(*v) ? (last = *v) : (*v = last);
  }
  return filled;
}

// Block length in nodes: configured seconds over the mean node interval, or sqrt(nodes) (the
// HAC's aggregation: blocks long against the residuals' memory, many per experiment).
int BlockNodes(const Experiment& e, double seconds) {
  const int n = e.num_nodes();
  if (n < 2) return 1;
  if (seconds <= 0.0) return std::max(1, static_cast<int>(std::lround(std::sqrt(n))));
  const double interval = (e.node_time.back() - e.node_time.front()) / (n - 1);
  return std::clamp(static_cast<int>(std::lround(seconds / interval)), 1, n);
}

struct BlockData {
  std::vector<std::vector<double>> d;                    // per experiment, per sample
  std::vector<std::vector<std::vector<double>>> filled;  // per experiment, output, node
  std::vector<int> block;                                // nodes per block, per experiment
};

// Replicate r's experiments of the block bootstrap: value* = value + d_i - d_source, i.e.
// y* = y_fit + (y - y_fit) at the node the block maps node k to.
std::vector<Experiment> BlockReplicate(const std::vector<Experiment>& original,
                                       const BlockData& data, unsigned seed, int r) {
  std::vector<Experiment> experiments = original;
  for (size_t e = 0; e < experiments.size(); ++e) {
    Experiment& x = experiments[e];
    const int n = x.num_nodes(), b = data.block[e];
    std::mt19937_64 rng(CaseSeed(seed, static_cast<int>(e), r));
    std::uniform_int_distribution<int> start(0, n - b);
    std::vector<int> source;
    source.reserve(n + b);
    while (static_cast<int>(source.size()) < n) {
      const int s = start(rng);
      for (int j = 0; j < b; ++j) source.push_back(s + j);
    }
    for (int k = 0; k < n; ++k) {
      for (int i = x.node_first_sample[k]; i < x.node_first_sample[k + 1]; ++i) {
        const double di = data.d[e][i];
        const double ds = data.filled[e][x.samples[i].output][source[k]];
        if (std::isfinite(di) && std::isfinite(ds)) x.samples[i].value += di - ds;
      }
    }
  }
  return experiments;
}

// Replicate r's experiments of the experiment bootstrap; drawn[e] = k, the times drawn.
std::vector<Experiment> ExperimentReplicate(const std::vector<Experiment>& original, unsigned seed,
                                            int r, std::vector<int>* drawn) {
  const int count = static_cast<int>(original.size());
  std::mt19937_64 rng(CaseSeed(seed, 0, r));
  std::uniform_int_distribution<int> pick(0, count - 1);
  drawn->assign(count, 0);
  for (int i = 0; i < count; ++i) ++(*drawn)[pick(rng)];
  std::vector<Experiment> experiments = original;
  for (int e = 0; e < count; ++e) {
    const double factor = std::sqrt(static_cast<double>((*drawn)[e]));
    for (ExperimentSample& s : experiments[e].samples) s.weight *= factor;
    experiments[e].prior_weight *= factor;
  }
  return experiments;
}

// Sample covariance over the replicates in which both variables take part (`present`).
Eigen::MatrixXd ReplicateCovariance(const std::vector<std::vector<double>>& values,
                                    const std::vector<std::vector<char>>& present) {
  const int m = values.empty() ? 0 : static_cast<int>(values[0].size());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Constant(m, m, kNaN);
  std::vector<double> mean(m, 0.0);
  std::vector<int> count(m, 0);
  for (size_t r = 0; r < values.size(); ++r) {
    for (int i = 0; i < m; ++i) {
      if (present[r][i]) mean[i] += values[r][i], ++count[i];
    }
  }
  for (int i = 0; i < m; ++i) mean[i] /= std::max(1, count[i]);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      int n = 0;
      for (size_t r = 0; r < values.size(); ++r) {
        if (!present[r][i] || !present[r][j]) continue;
        sum += (values[r][i] - mean[i]) * (values[r][j] - mean[j]);
        ++n;
      }
      if (n >= 2) cov(i, j) = cov(j, i) = sum / (n - 1);
    }
  }
  return cov;
}

}  // namespace

std::string ExperimentBootstrapRefusal(const std::string& stage, int count) {
  return "experiment_bootstrap in stage '" + stage + "' needs at least " +
         std::to_string(kMinBootstrapExperiments) + " experiments or segments to resample, it has " +
         std::to_string(count) +
         " (cut the records into segments with `segment_length`, or use block_bootstrap)";
}

void BootstrapStageUncertainty(const StageOptions& options, const OutputErrorOptions& problem_options,
                               OutputErrorProblem* solved, StageSummary* summary) {
  const BootstrapOptions& boot = options.uncertainty.bootstrap;
  const bool blocks = options.uncertainty.method == UncertaintyMethod::kBlockBootstrap;
  const char* method = UncertaintyMethodToString(options.uncertainty.method);
  const Uncertainty& kept = summary->uncertainty;
  const std::string keeping = std::string("; the ") + kept.method + " covariance is reported";
  const std::vector<Experiment>& original = solved->experiments();
  const int count = static_cast<int>(original.size());
  if (blocks && solved->filter_error()) {
    // Its pseudo-records are the simulation plus resampled output-error residuals; the
    // filter's innovations would have to be fed back through the filter to make records.
    summary->findings.push_back(MakeFinding(
        FindingKind::kBootstrap,
        std::string(method) + " in stage '" + options.name +
            "' resamples output error's residuals onto its simulation; under the filter-error "
            "method (noise:) it is not run: experiment_bootstrap resamples whole runs or "
            "segments and refits them" + keeping));
    return;
  }
  if (!blocks && count < kMinBootstrapExperiments) {
    summary->findings.push_back(MakeFinding(
        FindingKind::kBootstrap, ExperimentBootstrapRefusal(options.name, count) + keeping));
    return;
  }
  // The variables reported: those of the stage's covariance, else every free one.
  std::vector<int> variables = kept.variables;
  if (variables.empty()) {
    for (size_t i = 0; i < solved->variables().size(); ++i) {
      if (solved->variables()[i].free) variables.push_back(static_cast<int>(i));
    }
  }
  const std::vector<ParameterSpec> specs = EstimateSpecs(*solved);
  const std::vector<double> estimate = solved->Values();
  BlockData data;
  double block_seconds = 0.0;
  if (blocks) {
    // A robust loss scales the residuals the problem returns: evaluate them without it.
    OutputErrorProblem* residuals = solved;
    std::unique_ptr<OutputErrorProblem> plain;
    if (problem_options.loss != "none") {
      OutputErrorOptions no_loss = problem_options;
      no_loss.loss = "none";
      std::string error;
      plain = OutputErrorProblem::Create(&solved->model(), original, specs, no_loss, &error);
      if (plain != nullptr && plain->variables().size() == estimate.size()) {
        plain->SetValues(estimate);
        residuals = plain.get();
      }
    }
    for (int e = 0; e < count; ++e) {
      std::vector<double> d;
      if (!SimulatedMinusMeasured(residuals, e, &d)) {
        summary->findings.push_back(MakeFinding(FindingKind::kBootstrap,
                                                std::string(method) + ": the residuals of " +
                                                    original[e].name +
                                                    " could not be evaluated" + keeping));
        return;
      }
      data.filled.push_back(NodeFilled(original[e], d));
      data.d.push_back(std::move(d));
      const Experiment& x = original[e];
      const int b = BlockNodes(x, boot.block_length);
      data.block.push_back(b);
      if (x.num_nodes() > 1) {
        block_seconds = std::max(block_seconds, b * (x.node_time.back() - x.node_time.front()) /
                                                    (x.num_nodes() - 1));
      }
    }
  }
  const StageOptions replicate_options = ReplicateOptions(options);

  const int runs = boot.runs;
  std::vector<std::vector<double>> values(runs);
  std::vector<std::vector<char>> present(runs);
  std::vector<char> solved_ok(runs, 0);
  ParallelFor(runs, boot.num_threads, [&](int r) {
    std::vector<int> drawn(count, 1);
    std::vector<Experiment> experiments =
        blocks ? BlockReplicate(original, data, boot.seed, r)
               : ExperimentReplicate(original, boot.seed, r, &drawn);
    std::unique_ptr<OutputErrorProblem> p = SolveReplicate(
        *solved, std::move(experiments), specs, problem_options, replicate_options);
    if (p == nullptr) return;
    const std::vector<double> v = p->Values();
    for (int index : variables) {
      const int e = p->variables()[index].experiment;
      values[r].push_back(v[index]);
      present[r].push_back(e < 0 || drawn[e] > 0);
    }
    solved_ok[r] = 1;
  });
  std::vector<std::vector<double>> good_values;
  std::vector<std::vector<char>> good_present;
  for (int r = 0; r < runs; ++r) {
    if (!solved_ok[r]) continue;
    good_values.push_back(std::move(values[r]));
    good_present.push_back(std::move(present[r]));
  }
  const int failed = runs - static_cast<int>(good_values.size());
  char text[512];
  if (static_cast<int>(good_values.size()) < kMinBootstrapRuns) {
    std::snprintf(text, sizeof(text), "%s: only %d of %d replicates solved", method,
                  runs - failed, runs);
    summary->findings.push_back(MakeFinding(FindingKind::kBootstrap, text + keeping));
    return;
  }
  if (failed > kBootstrapFailureWarning * runs) {
    std::snprintf(text, sizeof(text),
                  "%s: %d of %d replicates failed to solve (more than %.0f %%); the "
                  "covariance comes from the %d that did and may be too narrow",
                  method, failed, runs, 100 * kBootstrapFailureWarning, runs - failed);
    Finding lost = MakeFinding(FindingKind::kBootstrap, text);
    lost.value = static_cast<double>(failed) / runs;
    lost.threshold = kBootstrapFailureWarning;
    summary->findings.push_back(std::move(lost));
  }
  Uncertainty u;
  u.available = true;
  u.variables = variables;
  u.covariance = ReplicateCovariance(good_values, good_present);
  u.undetermined = kept.undetermined;
  u.undetermined_variables = kept.undetermined_variables;
  u.residual_variance = kept.residual_variance;
  SetStdErrorsAndCorrelation(&u);
  u.method = method;
  u.bootstrap_runs = runs;
  u.bootstrap_failed = failed;
  u.block_length = block_seconds;
  u.replicates = good_values;
  for (int index : variables) u.replicate_names.push_back(solved->variables()[index].name);
  // The Hessian's standard errors beside, in the same variable order.
  if (kept.available && kept.variables == variables) {
    u.hessian_std_errors = kept.method == "hessian" ? kept.std_errors : kept.hessian_std_errors;
  }
  if (blocks) {
    std::snprintf(text, sizeof(text), "configured: %d replicates (%d failed), blocks of %.3g s%s",
                  runs, failed, block_seconds, boot.block_length > 0.0 ? "" : " (sqrt of the nodes)");
  } else {
    std::snprintf(text, sizeof(text), "configured: %d replicates (%d failed) of %d experiments",
                  runs, failed, count);
  }
  u.method_reason = text;
  // A variable every replicate leaves at one value (held by a bound): its SE 0 says nothing.
  std::string constant;
  for (size_t i = 0; i < variables.size(); ++i) {
    if (u.std_errors[i] == 0.0) {
      constant += (constant.empty() ? "" : ", ") + solved->variables()[variables[i]].name;
    }
  }
  if (!constant.empty()) {
    Finding held = MakeFinding(FindingKind::kBootstrap,
                               std::string(method) + ": " + constant +
                                   " took the same value in every replicate (held by a bound): "
                                   "the standard error 0 does not measure its uncertainty");
    held.parameter = constant;
    summary->findings.push_back(std::move(held));
  }
  summary->uncertainty = std::move(u);
}

}  // namespace vesselid
