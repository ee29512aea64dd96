#include "engine/solve/noise_weights.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vesselid {

std::vector<double> NoiseModel::Weights(const ModelInfo& info) const {
  std::vector<double> weights(info.outputs.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 0; k < outputs.size(); ++k) {
    const int c = info.OutputIndex(outputs[k]);
    if (c >= 0) weights[c] = 1.0 / sigma[k];
  }
  return weights;
}

bool SetDataNoiseWeights(OutputErrorProblem* problem) {
  const size_t ny = problem->model().info().outputs.size();
  std::vector<double> power(ny, 0.0), count(ny, 0.0);
  for (const Experiment& e : problem->experiments()) {
    for (size_t c = 0; c < ny && c < e.channel_noise_power.size(); ++c) {
      if (e.output_sample_count[c] == 0) continue;
      power[c] += e.channel_noise_power[c];
      count[c] += std::isfinite(e.NoiseLevel(static_cast<int>(c))) ? e.output_sample_count[c]
                                                                   : 0.0;
    }
  }
  std::vector<double> weights(ny, std::numeric_limits<double>::quiet_NaN());
  bool any = false;
  for (const Experiment& e : problem->experiments()) {
    for (size_t c = 0; c < ny; ++c) {
      if (e.output_sample_count[c] == 0) continue;  // not compared here
      const double sigma = count[c] > 0.0 ? std::sqrt(power[c] / count[c]) : 0.0;
      if (!(sigma > 0.0) || !std::isfinite(sigma)) return false;
      weights[c] = 1.0 / sigma;
      any = true;
    }
  }
  if (!any) return false;
  problem->SetChannelWeights(weights);
  return true;
}

bool EstimateChannelNoise(const OutputErrorProblem& problem, const std::vector<ExperimentFit>& fits,
                          NoiseModel* noise, std::string* error) {
  const ModelInfo& info = problem.model().info();
  const size_t ny = info.outputs.size();
  std::vector<double> sse(ny, 0.0);
  std::vector<int> count(ny, 0);
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) {
      const int c = info.OutputIndex(m.output);
      if (c < 0) continue;
      sse[c] += m.rmse * m.rmse * m.samples;
      count[c] += m.samples;
    }
  }
  const double m = problem.num_residuals(), n = problem.num_free();
  const double dof = m > n ? m / (m - n) : 1.0;
  noise->outputs.clear();
  noise->sigma.clear();
  noise->samples.clear();
  for (size_t c = 0; c < ny; ++c) {
    if (count[c] == 0) continue;
    const double sigma = std::sqrt(sse[c] / count[c] * dof);
    if (!(sigma > 0.0) || !std::isfinite(sigma)) {
      *error = "output " + info.outputs[c] + " has no residual to estimate its noise from " +
               "(sigma " + std::to_string(sigma) + ")";
      return false;
    }
    noise->outputs.push_back(info.outputs[c]);
    noise->sigma.push_back(sigma);
    noise->samples.push_back(count[c]);
  }
  if (noise->outputs.empty()) {
    *error = "no compared output";
    return false;
  }
  return true;
}

bool IterateNoiseWeights(const StageOptions& options, OutputErrorProblem* problem,
                         StageSummary* summary, NoiseModel* noise) {
  NoiseModel current;
  std::string reason;
  if (!EstimateChannelNoise(*problem, summary->fits, &current, &reason)) {
    summary->findings.push_back(MakeFinding(
        FindingKind::kNoiseModel, "noise weights not applied, the configured weights stay: " + reason));
    return true;
  }
  StageOptions again_options = options;
  again_options.use_global_start = false;
  again_options.local.initial_radius = kNearOptimumRadius;
  // The re-solves start from the first solve's optimum; its global search stays reported.
  const GlobalStartSummary first_global = summary->global;
  // The first solve's global search stays reported: its narrative and its finding.
  std::vector<std::string> first_notes;
  for (const std::string& note : summary->notes) {
    if (note.rfind("global start", 0) == 0) first_notes.push_back(note);
  }
  const std::vector<Finding> first_findings = summary->findings;
  double time = summary->time_seconds;
  double change = 0.0;
  std::string largest;
  current.method = "noise";
  for (int k = 1; k <= kNoiseMaxResolves; ++k) {
    problem->SetChannelWeights(current.Weights(problem->model().info()));
    StageSummary again;
    if (!RunStage(again_options, problem, &again)) {
      summary->message = "re-solve " + std::to_string(k) + " with noise weights: " + again.message;
      return false;
    }
    time += again.time_seconds;
    again.name = summary->name;
    again.global = first_global;
    again.notes.insert(again.notes.begin(), first_notes.begin(), first_notes.end());
    for (const Finding& f : first_findings) {
      if (f.kind == FindingKind::kGlobalStartDiverged) again.findings.insert(again.findings.begin(), f);
    }
    *summary = std::move(again);
    NoiseModel next;
    if (!EstimateChannelNoise(*problem, summary->fits, &next, &reason)) {
      summary->message = "noise weights after re-solve " + std::to_string(k) + ": " + reason;
      return false;
    }
    change = 0.0;
    for (size_t i = 0; i < next.sigma.size() && i < current.sigma.size(); ++i) {
      const double relative = std::abs(next.sigma[i] / current.sigma[i] - 1.0);
      if (relative >= change) {
        change = relative;
        largest = next.outputs[i];
      }
    }
    next.method = "noise";
    next.iterations = k;
    next.converged = change < kNoiseTolerance;
    current = std::move(next);
    if (change < kNoiseTarget) break;
  }
  summary->time_seconds = time;
  if (!current.converged) {
    char text[256];
    std::snprintf(text, sizeof(text),
                  "the noise model did not settle in %d re-solves (sigma of %s still changed by "
                  "%.1f %%); the weights are those of the last estimate",
                  kNoiseMaxResolves, largest.c_str(), 100.0 * change);
    Finding unsettled = MakeFinding(FindingKind::kNoiseModel, text);
    unsettled.output = largest;
    unsettled.value = change;
    unsettled.threshold = kNoiseTolerance;
    summary->findings.push_back(std::move(unsettled));
  }
  *noise = std::move(current);
  return true;
}

}  // namespace vesselid
