#include "engine/run/disturbance_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "engine/run/disturbance_notes.h"
#include "engine/run/estimate_specs.h"

namespace vesselid {
namespace {

// Put before the outlier screen's findings when a filter is chosen.
constexpr char kOutputErrorsFit[] =
    "in output error's fit, before the disturbance model was chosen: ";

// The lag-1 autocorrelation above which residuals judged noise-free are the integrator's
// smooth error (the cargo example: 0.96).
constexpr double kIntegrationErrorLag1 = 0.9;

// States whose equation the inputs drive: df_i/du != 0 at the first node of the first
// experiment (forward differences of the model's right-hand side).
std::vector<int> InputDrivenStates(const ModelHandle& model, const OutputErrorProblem& solved) {
  const ModelInfo& info = model.info();
  const size_t nx = info.states.size(), nu = info.inputs.size();
  std::vector<int> states;
  if (solved.experiments().empty() || nu == 0) return states;
  const Experiment& e = solved.experiments().front();
  const std::vector<double> p = solved.ParametersOf(0), x = solved.InitialStateOf(0);
  std::vector<double> u(e.input_cache.begin(), e.input_cache.begin() + nu);
  std::vector<double> f0(nx), f1(nx);
  if (!model.Derivative(x.data(), u.data(), p.data(), f0.data())) return states;
  std::vector<bool> driven(nx, false);
  for (size_t i = 0; i < nu; ++i) {
    if (!std::isfinite(u[i])) continue;
    std::vector<double> v = u;
    const double step = 1e-4 * std::max(1.0, std::abs(u[i]));
    v[i] += step;
    if (!model.Derivative(x.data(), v.data(), p.data(), f1.data())) continue;
    for (size_t s = 0; s < nx; ++s) driven[s] = driven[s] || std::abs(f1[s] - f0[s]) > 1e-12;
  }
  for (size_t s = 0; s < nx; ++s) {
    if (driven[s]) states.push_back(static_cast<int>(s));
  }
  return states;
}

// A note of how far the chosen model moved the ship's estimates from output error's, in
// combined SEs (the largest over the shared free parameters). Not a finding: strong process
// noise throws output error's own estimate off (16 SE on a record whose gusts moved the heading
// by degrees, the chosen model's estimate within 0.3 SE of the truth), as does an output-error
// estimate held at a bound; the innovation test (innovation_structure.h) tells structure.
void AddDisagreement(const OutputErrorProblem& oe, const Uncertainty& oe_uncertainty,
                     const OutputErrorProblem& chosen, const Uncertainty& chosen_uncertainty,
                     const std::string& name, StageSummary* summary) {
  std::map<std::string, std::pair<double, double>> oe_values;  // name: value, SE
  for (size_t i = 0; i < oe.variables().size(); ++i) {
    const Variable& v = oe.variables()[i];
    if (v.kind == Variable::Kind::kParameter && v.free && v.experiment < 0) {
      oe_values[v.name] = {v.value(), oe_uncertainty.StdError(static_cast<int>(i))};
    }
  }
  double worst = 0.0;
  std::string which;
  for (size_t i = 0; i < chosen.variables().size(); ++i) {
    const Variable& v = chosen.variables()[i];
    const auto found = oe_values.find(v.name);
    if (v.kind != Variable::Kind::kParameter || found == oe_values.end()) continue;
    const double se = chosen_uncertainty.StdError(static_cast<int>(i));
    const double combined = std::hypot(se, found->second.second);
    if (!(combined > 0.0) || !std::isfinite(combined)) continue;
    const double z = std::abs(v.value() - found->second.first) / combined;
    if (z > worst) {
      worst = z;
      which = v.name;
    }
  }
  if (which.empty()) return;
  char text[320];
  std::snprintf(text, sizeof(text),
                "noise auto: the chosen model (%s) moves %s %.1f combined standard errors from "
                "output error's estimate%s",
                name.c_str(), which.c_str(), worst,
                worst > kStructureDisagreement
                    ? ": structure the noise absorbs, or output error thrown off by strong "
                      "process noise (the innovation structure test tells them apart)"
                    : "");
  summary->notes.push_back(text);
}

// The median interval between output j's samples over the problem's experiments (s).
double SampleInterval(const OutputErrorProblem& problem, int j) {
  std::vector<double> intervals;
  for (const Experiment& e : problem.experiments()) {
    double last = NAN;
    for (int k = 0; k < e.num_nodes(); ++k) {
      for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
        if (e.samples[i].output != j) continue;
        if (std::isfinite(last)) intervals.push_back(e.node_time[k] - last);
        last = e.node_time[k];
      }
    }
  }
  if (intervals.empty()) return NAN;
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return intervals[intervals.size() / 2];
}

// omega of an oscillating autocorrelation (see the wave candidate), NaN when it does not
// oscillate within its lags.
double OscillationFrequency(const ResidualAnalysis& a, double dt) {
  const std::vector<double>& r = a.autocorrelation;
  for (size_t lag = 1; lag < r.size(); ++lag) {
    if (!(r[lag] < 0.0)) continue;
    const double crossing = lag - 1 + r[lag - 1] / (r[lag - 1] - r[lag]);  // linear
    const double lowest = *std::min_element(r.begin() + lag, r.end());
    if (lowest > -0.2 || !(dt > 0.0)) return NAN;
    return M_PI / 2.0 / (crossing * dt);
  }
  return NAN;
}

}  // namespace

std::vector<DisturbanceCandidate> DisturbanceCandidates(
    const ModelHandle& model, const OutputErrorProblem& solved,
    const std::vector<ResidualAnalysis>& residuals) {
  const ModelInfo& info = model.info();
  std::vector<DisturbanceCandidate> candidates;
  DisturbanceCandidate oe;
  oe.name = "output_error";
  candidates.push_back(oe);
  DisturbanceSpec base;
  base.method = DisturbanceSpec::Method::kFilterError;
  DisturbanceCandidate white;
  white.name = "white";
  white.spec = base;
  candidates.push_back(white);
  std::vector<std::string> coloured;
  for (const ResidualAnalysis& a : residuals) {
    if (a.coloured() &&
        std::find(coloured.begin(), coloured.end(), a.output) == coloured.end()) {
      coloured.push_back(a.output);
    }
  }
  DisturbanceSpec ar1 = base;
  for (const std::string& output : coloured) {
    DisturbanceSpec::Measurement m;
    m.output = output;
    m.type = DisturbanceSpec::Measurement::Type::kAr1;
    m.white_too = true;
    ar1.measurement.push_back(m);
  }
  DisturbanceSpec process = base;
  for (int s : InputDrivenStates(model, solved)) {
    DisturbanceSpec::Process w;
    w.state = info.states[s];
    process.process.push_back(w);
  }
  if (!ar1.measurement.empty()) {
    DisturbanceCandidate c;
    c.spec = ar1;
    c.name = "ar1(" + JoinNames(coloured) + ")";
    candidates.push_back(c);
  }
  // Residuals that oscillate (their autocorrelation crosses zero and swings below -0.2): a
  // narrow-band part, wave-frequency yaw, with its peak frequency started from the first
  // zero crossing (r(t) ~ cos(omega t) e^(-zeta omega t) crosses at omega t = pi / 2).
  DisturbanceSpec wave = base;
  std::vector<std::string> waving;
  for (const ResidualAnalysis& a : residuals) {
    const int j = info.OutputIndex(a.output);
    if (!a.coloured() || j < 0 || std::find(waving.begin(), waving.end(), a.output) != waving.end()) {
      continue;
    }
    const double omega = OscillationFrequency(a, SampleInterval(solved, j));
    if (!(omega > 0.0)) continue;
    DisturbanceSpec::Wave w;
    w.output = a.output;
    w.omega = omega;
    wave.wave.push_back(w);
    waving.push_back(a.output);
  }
  if (!wave.wave.empty()) {
    DisturbanceCandidate c;
    c.spec = wave;
    c.name = "wave(" + JoinNames(waving) + ")";
    candidates.push_back(c);
  }
  if (!process.process.empty()) {
    DisturbanceCandidate c;
    c.spec = process;
    std::vector<std::string> names;
    for (const auto& w : process.process) names.push_back(w.state);
    c.name = "process(" + JoinNames(names) + ")";
    candidates.push_back(c);
    if (!ar1.measurement.empty()) {
      DisturbanceCandidate both;
      both.spec = ar1;
      both.spec.process = process.process;
      both.name = candidates[2].name + " + " + c.name;
      candidates.push_back(both);
    }
  }
  return candidates;
}

void NameFilterErrorUncertainty(const UncertaintyOptions& configured, Uncertainty* u) {
  if (configured.method == UncertaintyMethod::kAuto && u->method_reason == "configured") {
    u->method_reason = "the filter-error method's default: the likelihood's Fisher information";
  }
}

UncertaintyOptions FilterErrorUncertainty(UncertaintyOptions options) {
  if (options.method == UncertaintyMethod::kAuto) options.method = UncertaintyMethod::kHessian;
  options.input_noise = false;
  return options;
}

double OutputErrorNegativeLogLikelihood(const OutputErrorProblem& problem) {
  const ModelInfo& info = problem.model().info();
  const size_t ny = info.outputs.size();
  std::vector<double> sse(ny, 0.0), count(ny, 0.0);
  std::vector<double> outputs;
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& x = problem.experiments()[e];
    const std::vector<double> p = problem.ParametersOf(static_cast<int>(e));
    const std::vector<double> x0 = problem.InitialStateOf(static_cast<int>(e));
    const std::vector<double> c = problem.InputCorrectionsOf(static_cast<int>(e));
    if (!problem.model().SimulateOutputs(x, p.data(), x0.data(), &outputs,
                                         c.empty() ? nullptr : c.data())) {
      return NAN;
    }
    for (int k = 0; k < x.num_nodes(); ++k) {
      for (int i = x.node_first_sample[k]; i < x.node_first_sample[k + 1]; ++i) {
        const ExperimentSample& s = x.samples[i];
        double r = outputs[static_cast<size_t>(k) * ny + s.output] - s.value;
        if (x.Wrapped(s.output)) r -= 2.0 * M_PI * std::round(r / (2.0 * M_PI));
        sse[s.output] += r * r;
        count[s.output] += 1.0;
      }
    }
  }
  double nll = 0.0;
  for (size_t j = 0; j < ny; ++j) {
    if (count[j] == 0.0) continue;
    const double variance = std::max(sse[j] / count[j], 1e-300);
    nll += 0.5 * count[j] * (std::log(2.0 * M_PI * variance) + 1.0);
  }
  return nll;
}

bool ChooseDisturbance(const StageConfig& stage, const StageOptions& options,
                       const std::vector<ResidualAnalysis>& residuals,
                       std::unique_ptr<OutputErrorProblem>* problem, StageSummary* summary,
                       std::vector<DisturbanceCandidate>* candidates, std::string* error) {
  OutputErrorProblem& oe = **problem;
  candidates->clear();
  // Noise-free data's residuals are the integrator's error, smooth and so coloured: no
  // disturbance to model (residual_analysis.h). Smooth means a lag-1 near 1: the noise-free
  // test alone (RMSE against the second differences' level) also passes slow real noise on
  // a ship that keeps turning, logged at 0.5 Hz (lag-1 0.24-0.64, a second user's records),
  // and output error alone left the truth 3.5 SE away there.
  const bool coloured =
      std::any_of(residuals.begin(), residuals.end(), [](const ResidualAnalysis& a) {
        return a.coloured() && !(a.noise_free && a.lag1 > kIntegrationErrorLag1);
      });
  if (!coloured) {
    summary->notes.push_back(
        "noise auto: output error kept, its residuals are white or noise-free data's "
        "integration error (no disturbance model needed)");
    return true;
  }
  *candidates = DisturbanceCandidates(oe.model(), oe, residuals);
  const double n = oe.num_samples();
  std::vector<std::unique_ptr<OutputErrorProblem>> solved(candidates->size());
  std::vector<StageSummary> summaries(candidates->size());
  std::map<std::string, double> oe_values;
  for (const Variable& v : oe.variables()) oe_values[v.name] = v.value();
  for (size_t c = 0; c < candidates->size(); ++c) {
    DisturbanceCandidate& candidate = (*candidates)[c];
    if (c == 0) {
      candidate.negative_log_likelihood = OutputErrorNegativeLogLikelihood(oe);
      // k: the free unknowns and one sigma per compared output.
      int outputs = 0;
      for (size_t j = 0; j < oe.model().info().outputs.size(); ++j) {
        for (const Experiment& e : oe.experiments()) {
          if (e.output_sample_count[j] > 0) {
            ++outputs;
            break;
          }
        }
      }
      candidate.unknowns = oe.num_free() + outputs;
      candidate.solved = std::isfinite(candidate.negative_log_likelihood);
    } else {
      StageConfig with = stage;
      with.problem.disturbance = candidate.spec;
      with.problem.loss = "none";
      StageOptions quiet = options;
      quiet.compute_uncertainty = false;  // only the chosen one's intervals, computed below
      // From output error's estimate; the combined candidate (AR(1) and process noise) from the
      // solutions of the simpler filters instead, white, AR(1) alone and process noise alone
      // (their noise parameters carried by name): its likelihood is then never below theirs,
      // which a start from output error did not guarantee (AR(1) + process noise stuck at the
      // AR(1) optimum with q at its floor). Not also from output error's estimate: the combined
      // candidate's solves, on the widest Jets, were most of auto's time, and that start
      // changed no choice or estimate on the noise-or-structure corpus or the real records
      // (docs/models.md). The white filter's start stays: without it the KVLCC2 records'
      // combined optimum was 138 worse in -log L.
      std::vector<const OutputErrorProblem*> starts;
      if (!candidate.spec.process.empty() && !candidate.spec.measurement.empty()) {
        for (size_t earlier = 1; earlier < c; ++earlier) {
          const DisturbanceSpec& nested = (*candidates)[earlier].spec;
          if (solved[earlier] != nullptr && nested.wave.empty()) {
            starts.push_back(solved[earlier].get());
          }
        }
      }
      if (starts.empty()) starts.push_back(&oe);
      std::unique_ptr<OutputErrorProblem> p;
      StageSummary trial;
      double best_nll = std::numeric_limits<double>::infinity();
      std::string why;
      for (const OutputErrorProblem* from : starts) {
        StageSummary attempt = *summary;
        std::unique_ptr<OutputErrorProblem> q =
            RefineFromEstimate(*from, oe.experiments(), with.problem, quiet, &attempt, &why);
        if (q == nullptr) continue;
        for (const LocalSolveSummary& r : attempt.refinements) candidate.iterations += r.iterations;
        const double nll = q->NegativeLogLikelihood();
        if (nll < best_nll) {
          best_nll = nll;
          p = std::move(q);
          trial = std::move(attempt);
        }
      }
      if (p == nullptr) {
        candidate.why = why;
        continue;
      }
      candidate.negative_log_likelihood = p->NegativeLogLikelihood();
      candidate.unknowns = p->num_free();
      candidate.solved = std::isfinite(candidate.negative_log_likelihood);
      solved[c] = std::move(p);
      summaries[c] = std::move(trial);
    }
    candidate.bic = 2.0 * candidate.negative_log_likelihood + candidate.unknowns * std::log(n);
  }
  size_t best = 0;
  for (size_t c = 1; c < candidates->size(); ++c) {
    if ((*candidates)[c].solved && (*candidates)[c].bic < (*candidates)[best].bic) best = c;
  }
  std::string table = "noise auto: BIC (2 -log L + k log N, N " +
                      std::to_string(static_cast<long>(n)) + ")";
  for (size_t c = 0; c < candidates->size(); ++c) {
    const DisturbanceCandidate& d = (*candidates)[c];
    char text[160];
    if (d.solved) {
      if (c == 0) {
        std::snprintf(text, sizeof(text), ": %s %.1f (k %d)%s", d.name.c_str(), d.bic,
                      d.unknowns, c == best ? " chosen" : "");
      } else {
        std::snprintf(text, sizeof(text), "; %s %.1f (k %d, %d iterations)%s",
                      d.name.c_str(), d.bic, d.unknowns, d.iterations,
                      c == best ? " chosen" : "");
      }
    } else {
      std::snprintf(text, sizeof(text), "%s %s not solved (%s)", c == 0 ? ":" : ";",
                    d.name.c_str(), d.why.c_str());
    }
    table += text;
  }
  if (best == 0) {
    summary->notes.push_back(table);
    return true;
  }
  // The winner solved again with its intervals.
  StageOptions final_options = options;
  final_options.uncertainty = FilterErrorUncertainty(options.uncertainty);
  StageConfig with = stage;
  with.problem.disturbance = (*candidates)[best].spec;
  with.problem.loss = "none";
  StageSummary chosen = *summary;
  std::unique_ptr<OutputErrorProblem> p =
      RefineFromEstimate(*solved[best], solved[best]->experiments(), with.problem, final_options,
                         &chosen, error);
  if (p == nullptr) return false;
  // The output-error solve's global start found the estimate every candidate started from.
  chosen.global = summary->global;
  // The outlier screen (output_error_stage.cc) judged output error's fit: its values are not
  // the chosen model's, and its finding says whose they are.
  for (Finding& f : chosen.findings) {
    if (f.kind == FindingKind::kOutliers && f.message.rfind(kOutputErrorsFit, 0) != 0) {
      f.message = kOutputErrorsFit + f.message;
    }
  }
  NameFilterErrorUncertainty(options.uncertainty, &chosen.uncertainty);
  AddDisagreement(oe, summary->uncertainty, *p, chosen.uncertainty, (*candidates)[best].name,
                  &chosen);
  std::string beside = "noise auto: output error's estimates were";
  for (size_t i = 0; i < oe.variables().size(); ++i) {
    const Variable& v = oe.variables()[i];
    if (v.kind != Variable::Kind::kParameter || !v.free || v.experiment >= 0) continue;
    // In the model's units, as the stage's estimates table gives them.
    const std::string unit = oe.model().info().ParameterUnit(v.index);
    char text[160];
    std::snprintf(text, sizeof(text), " %s %.6g%s%s (SE %.2g)", v.name.c_str(), v.value(),
                  unit.empty() ? "" : " ", unit.c_str(),
                  summary->uncertainty.StdError(static_cast<int>(i)));
    beside += text;
  }
  chosen.notes.push_back(table);
  chosen.notes.push_back(beside);
  *problem = std::move(p);
  *summary = std::move(chosen);
  return true;
}

DisturbanceReport ReportDisturbance(const DisturbanceSpec& spec, const OutputErrorProblem& problem,
                                    const Uncertainty& uncertainty,
                                    const std::vector<DisturbanceCandidate>& candidates) {
  DisturbanceReport report;
  const bool automatic = spec.method == DisturbanceSpec::Method::kAuto;
  if (!automatic && !problem.filter_error()) return report;
  report.method = automatic ? "auto" : "filter_error";
  report.filter_error = problem.filter_error();
  report.model = problem.filter_error() ? DescribeDisturbance(problem, uncertainty)
                                        : "none: output error kept";
  report.negative_log_likelihood = problem.filter_error() ? problem.NegativeLogLikelihood()
                                                          : OutputErrorNegativeLogLikelihood(problem);
  size_t best = 0;
  for (size_t c = 1; c < candidates.size(); ++c) {
    if (candidates[c].solved && candidates[c].bic < candidates[best].bic) best = c;
  }
  for (size_t c = 0; c < candidates.size(); ++c) {
    const DisturbanceCandidate& d = candidates[c];
    DisturbanceCandidateScore score;
    score.name = d.name;
    score.solved = d.solved;
    score.why = d.why;
    if (d.solved) {
      score.negative_log_likelihood = d.negative_log_likelihood;
      score.bic = d.bic;
    }
    score.unknowns = d.unknowns;
    score.chosen = d.solved && c == best;
    report.candidates.push_back(score);
  }
  return report;
}

}  // namespace vesselid
