#include "engine/design/design_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>

#include "engine/base/memory_budget.h"
#include "engine/design/design_criterion.h"
#include "engine/design/design_limits.h"
#include "engine/design/design_names.h"
#include "engine/design/design_search.h"
#include "engine/design/input_commands.h"
#include "engine/export/model_json.h"
#include "engine/export/run_folder_model.h"

namespace vesselid {
namespace {

// False, saying which keys and figures, when a planned log of `duration` s at `sample_time`
// would not fit the memory budget: each sample holds the inputs and outputs and, for the
// information, the outputs' sensitivities to the parameters and states, for the plan and the
// alternatives the two cores evaluate at once.
bool PlannedLogFits(const ModelInfo& info, double duration, double sample_time,
                    std::string* error) {
  const double samples = std::floor(duration / sample_time) + 1.0;
  const double per_sample =
      8.0 * (info.inputs.size() + info.outputs.size() +
             info.outputs.size() * (info.parameters.size() + info.states.size())) * 4.0;
  const double need = samples * per_sample;
  if (samples < 2e9 && need <= static_cast<double>(MemoryBudget())) return true;
  char text[320];
  std::snprintf(text, sizeof(text),
                "design.duration / design.sample_time: a planned log of %.4g samples (%.4g s "
                "at %.4g s) needs %s, more than the memory budget of %s (half this machine's "
                "memory); log less often or plan a shorter run",
                samples, duration, sample_time, FormatBytes(need).c_str(),
                FormatBytes(static_cast<double>(MemoryBudget())).c_str());
  *error = text;
  return false;
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Per model output: the RMS residual of the run's last model stage's fit pooled over its
// experiments, in the model's units (the metrics are in the units the data came in: degrees
// back to radians).
std::vector<double> FitNoise(const RunDocument& run, const ModelInfo& info) {
  std::vector<double> sum(info.outputs.size(), 0.0), count(info.outputs.size(), 0.0);
  for (const RunDocument::Metric& m : run.fit_metrics) {
    const int o = NameIndex(info.outputs, m.output);
    if (o < 0 || !std::isfinite(m.rmse) || !(m.samples > 0)) continue;
    const double scale = m.unit == "deg" || m.unit == "deg/s" ? kDesignDegree : 1.0;
    sum[o] += m.samples * (m.rmse * scale) * (m.rmse * scale);
    count[o] += m.samples;
  }
  std::vector<double> sigma(info.outputs.size(), std::nan(""));
  for (size_t o = 0; o < sigma.size(); ++o) {
    if (count[o] > 0) sigma[o] = std::sqrt(sum[o] / count[o]);
  }
  return sigma;
}

double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  if (v.empty()) return std::nan("");
  const double position = q * static_cast<double>(v.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, v.size() - 1);
  if (!std::isfinite(v[above])) return v[above];
  return v[below] + (position - below) * (v[above] - v[below]);
}

PlanSummary Summarise(const std::string& name, PlanEvaluation e, const DesignResult& r) {
  PlanSummary s;
  s.name = name;
  s.ok = e.ok;
  s.error = e.error;
  if (!e.ok) return s;
  s.std_errors = e.member_std_errors.front();
  s.criterion = e.criterion;
  s.box_violation = e.box_violation;
  s.duration = e.record.time.empty() ? 0.0 : e.record.time.back();
  s.record = std::move(e.record);
  if (e.member_std_errors.size() > 1) {
    for (size_t i = 0; i < s.std_errors.size(); ++i) {
      std::vector<double> values;
      for (const std::vector<double>& m : e.member_std_errors) values.push_back(m[i]);
      s.std_error_low.push_back(Percentile(values, 0.05));
      s.std_error_median.push_back(Percentile(values, 0.5));
      s.std_error_high.push_back(Percentile(values, 0.95));
    }
  }
  if (r.widest >= 0) s.shrink = r.current_std_errors[r.widest] / s.std_errors[r.widest];
  return s;
}

// The model's names and units in the result, the inputs planned in degrees marked.
void DescribeModel(const IdentifiedModel& model, const ModelInfo& info, const DesignOptions& options,
                   DesignResult* r) {
  r->model = model.model;
  r->family = model.family;
  r->options = options;
  r->inputs = info.inputs;
  r->outputs = info.outputs;
  for (size_t i = 0; i < info.inputs.size(); ++i) {
    r->input_units.push_back(info.InputUnit(static_cast<int>(i)));
    bool degrees = false;
    for (const DesignInput& in : options.inputs)
      degrees = degrees || (in.name == info.inputs[i] && in.degrees);
    r->input_degrees.push_back(degrees);
  }
  for (size_t o = 0; o < info.outputs.size(); ++o)
    r->output_units.push_back(info.OutputUnit(static_cast<int>(o)));
}

// The parameters designed for (the run's free ones) and the plan's nuisance (its
// per-experiment ones); their values, standard errors and scales; today's information over
// them (the covariance's pseudo-inverse: a parameter the run left undetermined has none); the
// one known worst relative to its scale.
bool DesignedParameters(const IdentifiedModel& model, const RunDocument& run, DesignContext* c,
                        DesignResult* r, std::string* error) {
  const ModelInfo& info = c->model->info();
  std::map<std::string, int> index;
  for (size_t i = 0; i < info.parameters.size(); ++i)
    index[info.parameters[i]] = static_cast<int>(i);
  for (const RunDocument::Parameter& p : run.parameters) {
    const auto found = index.find(p.name);
    if (found == index.end()) continue;
    if (p.role == "free") c->setup.parameters.push_back(found->second);
    if (p.role == "per_experiment") c->setup.nuisance.push_back(found->second);
  }
  if (c->setup.parameters.empty()) {
    *error = model.results + ": the run estimated no model parameter to plan for";
    return false;
  }
  const int n = static_cast<int>(c->setup.parameters.size());
  for (int a = 0; a < n; ++a) {
    const int i = c->setup.parameters[a];
    r->parameters.push_back(info.parameters[i]);
    r->parameter_units.push_back(info.ParameterUnit(i));
    r->values.push_back(model.values[i]);
    const double se = model.std_errors[i];
    r->current_std_errors.push_back(std::isfinite(se) ? se : kInfinity);
    c->scale.push_back(std::abs(model.values[i]) > 0.0 ? std::abs(model.values[i])
                       : std::isfinite(se) && se > 0.0 ? se
                                                       : 1.0);
  }
  c->current = Eigen::MatrixXd::Zero(n, n);
  const Eigen::MatrixXd known = InformationOfCovariance(model.covariance);
  std::vector<int> row(model.covariance_names.size(), -1);
  for (size_t k = 0; k < row.size(); ++k) row[k] = NameIndex(r->parameters, model.covariance_names[k]);
  for (size_t a = 0; a < row.size(); ++a) {
    for (size_t b = 0; b < row.size(); ++b) {
      if (row[a] >= 0 && row[b] >= 0) c->current(row[a], row[b]) = known(a, b);
    }
  }
  double widest = -1.0;
  for (int a = 0; a < n; ++a) {
    const double relative = r->current_std_errors[a] / c->scale[a];
    if (relative > widest) {
      widest = relative;
      r->widest = a;
    }
  }
  return true;
}

// The plan's log: its sample time (the logger's: the information grows with the samples), the
// integration step, each output's noise (the fit's, or given), the start, the initial states
// it estimates (given, or the run's last model stage's), the box and the criterion.
bool PlanLog(const IdentifiedModel& model, const RunDocument& run, const DesignOptions& options,
             DesignContext* c, DesignResult* r, std::string* error) {
  const ModelInfo& info = c->model->info();
  r->sample_time = options.sample_time;
  if (!(r->sample_time > 0.0)) {
    *error = "design.sample_time: needed (the sample interval the planned run will be logged at)";
    return false;
  }
  c->sample_time = r->sample_time;
  c->setup.max_step = run.has_model_stage && std::isfinite(run.integration_step)
                          ? run.integration_step
                          : 0.0;
  if (!(c->setup.max_step > 0.0)) c->setup.max_step = model.max_step;
  if (!(c->setup.max_step > 0.0)) c->setup.max_step = r->sample_time;
  const std::vector<double> fit_noise = FitNoise(run, info);
  r->noise.assign(info.outputs.size(), std::nan(""));
  for (size_t o = 0; o < info.outputs.size(); ++o) r->noise[o] = fit_noise[o];
  for (const auto& [name, sigma] : options.noise) {
    const int o = NameIndex(info.outputs, name);
    if (o < 0) {
      *error = "design.noise." + name + ": the model has no output '" + name + "'";
      return false;
    }
    r->noise[o] = sigma;
  }
  c->setup.sigma = r->noise;
  c->x0.assign(info.states.size(), 0.0);
  for (const auto& [name, value] : options.initial_state) {
    const int s = NameIndex(info.states, name);
    if (s < 0) {
      *error = "design.initial_state." + name + ": the model has no state '" + name + "'";
      return false;
    }
    c->x0[s] = value;
  }
  std::vector<std::string> free_states = options.free_initial_states;
  if (!options.free_initial_states_given) {
    for (const std::string& name : run.free_initial_states) {
      if (std::find(free_states.begin(), free_states.end(), name) == free_states.end()) {
        free_states.push_back(name);
      }
    }
  }
  for (const std::string& name : free_states) {
    const int s = NameIndex(info.states, name);
    if (s < 0) {
      *error = "design.free_initial_states: the model has no state '" + name + "'";
      return false;
    }
    c->setup.free_states.push_back(s);
  }
  for (const auto& [name, range] : options.box) {
    const int o = NameIndex(info.outputs, name);
    if (o < 0) {
      *error = "design.box." + name + ": the model has no output '" + name + "'";
      return false;
    }
    c->box.push_back({o, range});
  }
  if (options.criterion == DesignCriterion::kParameter) {
    c->criterion_parameter = NameIndex(r->parameters, options.parameter);
    if (c->criterion_parameter < 0) {
      *error = "design.criterion.parameter: '" + options.parameter +
               "' is not among the run's estimated parameters";
      return false;
    }
  }
  r->criterion = options.criterion == DesignCriterion::kD   ? "D"
                 : options.criterion == DesignCriterion::kA ? "A"
                 : options.criterion == DesignCriterion::kE ? "E"
                                                            : "parameter " + options.parameter;
  return true;
}

// The ensemble flown, the layout and actuators, the settled start, and the duration: given, or
// the current model's 20/20 zigzag to its fourth reversal; the planned log checked to fit.
bool PlanDuration(const IdentifiedModel& model, const DesignOptions& options, DesignContext* c,
                  DesignResult* r, std::string* error) {
  const ModelHandle& handle = *c->model;
  const ModelInfo& info = handle.info();
  c->options = options;
  c->members = {model.values};
  for (const std::vector<double>& member : model.ensemble) c->members.push_back(member);
  r->members = options.ensemble_members > 0 ? static_cast<int>(c->members.size()) : 0;
  if (!MakeDesignLayout(info, options, 1.0, &c->layout, error)) return false;
  c->actuators = MakeActuators(info, options, c->layout);
  if (options.settle > 0.0 && !SettleState(handle, model.values, options.settle,
                                           c->setup.max_step, c->actuators.start, &c->x0)) {
    *error = "design.settle: the current model diverges at the inputs' values";
    return false;
  }
  r->duration = options.duration;
  if (!(r->duration > 0.0)) {
    if (c->layout.rudder < 0 || c->layout.heading < 0) {
      *error =
          "design.duration: needed (the model has no rudder 'delta' and heading 'psi' for "
          "the default, a 20/20 zigzag's duration)";
      return false;
    }
    Manoeuvre zigzag = Zigzag(options, c->layout, 20 * kDesignDegree, 20 * kDesignDegree);
    zigzag.stop_after = 4;
    PlannedRecord record;
    constexpr double kLongest = 7200.0;
    if (!PlannedLogFits(info, kLongest, r->sample_time, error)) return false;
    if (!RealizePlan(handle, model.values, c->x0, kLongest, r->sample_time, c->setup.max_step,
                     c->actuators, zigzag.command, &record, zigzag.Stop()) ||
        *zigzag.reversals < 4) {
      *error = "design.duration: the current model does not complete a 20/20 zigzag within " +
               std::to_string(static_cast<int>(kLongest)) + " s; give the duration in s";
      return false;
    }
    r->duration = record.time.back();
    char note[120];
    std::snprintf(note, sizeof(note),
                  "duration: the 20/20 zigzag's to its fourth rudder reversal, %.1f s", r->duration);
    r->notes.push_back(note);
  }
  return PlannedLogFits(info, r->duration, r->sample_time, error) &&
         StepsFitTheSearch(options, r->duration, error) &&
         MakeDesignLayout(info, options, r->duration, &c->layout, error);
}

// The search for the plan, the standard alternatives flown the same way, and every plan
// checked against the limits it was made within.
bool SearchAndCompare(const DesignOptions& options, const DesignContext& c, DesignResult* r,
                      std::string* error) {
  SearchResult search;
  if (!SearchDesign(c, &search, error)) return false;
  r->design_variables = search.z;
  r->evaluations = search.evaluations;
  r->algorithm = search.algorithm;
  r->planned = Summarise("planned", std::move(search.best), *r);
  // Each alternative made again per simulation: a manoeuvre keeps its own state.
  for (const auto& alternative : Alternatives(options, c.layout)) {
    const std::string label = alternative.first;
    PlanEvaluation e = EvaluatePlan(
        c,
        [&options, &c, label]() {
          for (auto& [other, m] : Alternatives(options, c.layout)) {
            if (other == label) return m;
          }
          return Manoeuvre();
        },
        true);
    r->alternatives.push_back(Summarise(label, std::move(e), *r));
  }
  r->limit_violations = CheckLimits(options, c.layout, c.actuators, r->planned.record, c.box,
                                    c.model->info().outputs, r->sample_time);
  if (r->planned.box_violation > 0.0) {
    char note[160];
    std::snprintf(note, sizeof(note),
                  "no plan found keeps every member's track inside the box: the best leaves it "
                  "by %.4g",
                  r->planned.box_violation);
    r->notes.push_back(note);
  }
  return true;
}

}  // namespace

bool PlanNextExperiment(const ModelRegistry& registry, const DesignOptions& options,
                        const std::string& run_dir, DesignResult* result, std::string* error) {
  IdentifiedModel model;
  RunDocument run;
  if (!ReadIdentifiedModel(run_dir, registry, options.ensemble_members, options.seed, &model, error,
                         &run)) {
    return false;
  }
  if (!options.family.empty() && options.family != model.family) {
    *error = "model.family: the config's is '" + options.family + "', the run's (" + run_dir +
             ") '" + model.family + "'";
    return false;
  }
  const std::shared_ptr<const ModelHandle> handle =
      registry.MakeModel(model.family, model.options, error);
  if (handle == nullptr) return false;
  DesignResult r;
  r.run = run_dir;
  DescribeModel(model, handle->info(), options, &r);
  DesignContext c;
  c.model = handle.get();
  if (!DesignedParameters(model, run, &c, &r, error) || !PlanLog(model, run, options, &c, &r, error) ||
      !PlanDuration(model, options, &c, &r, error) || !SearchAndCompare(options, c, &r, error)) {
    return false;
  }
  *result = std::move(r);
  return true;
}

}  // namespace vesselid
