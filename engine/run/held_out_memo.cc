#include "engine/run/held_out_memo.h"

#include <algorithm>
#include <cmath>

#include "engine/run/records.h"

namespace vesselid {
namespace {

// The same fits: same outputs, step, weighting, rate window and limits (a state guess is the
// model's: set in both or in neither), and the same solver settings for the runs' own
// unknowns (threads aside: results do not depend on them).
bool SameSettings(const HeldOutRequest& a, const HeldOutRequest& b) {
  const LocalSolveOptions &lx = a.local, &ly = b.local;
  return SameSimulation(a.options, b.options) && lx.trust_region == ly.trust_region && lx.linear_solver == ly.linear_solver &&
         lx.max_iterations == ly.max_iterations && lx.function_tolerance == ly.function_tolerance &&
         lx.gradient_tolerance == ly.gradient_tolerance &&
         lx.parameter_tolerance == ly.parameter_tolerance &&
         lx.max_time_seconds == ly.max_time_seconds && !lx.keep_going && !ly.keep_going;
}

bool SameStart(const HeldOutStart& a, const HeldOutStart& b) {
  return a.mode == b.mode && a.burn_in == b.burn_in && a.implausible_sds == b.implausible_sds &&
         a.prior.apply == b.prior.apply && a.prior.scale == b.prior.scale &&
         a.prior.bounds == b.prior.bounds;
}

bool SamePerRun(const HeldOutPerRun& a, const HeldOutPerRun& b) {
  if (a.mode != b.mode || a.fit_start != b.fit_start ||
      a.parameters.size() != b.parameters.size() || a.spread.size() != b.spread.size()) {
    return false;
  }
  for (size_t k = 0; k < a.spread.size(); ++k) {
    if (a.spread[k] != b.spread[k] && !(std::isnan(a.spread[k]) && std::isnan(b.spread[k])))
      return false;
  }
  for (size_t k = 0; k < a.parameters.size(); ++k) {
    const ParameterSpec &x = a.parameters[k], &y = b.parameters[k];
    if (x.name != y.name || x.start != y.start || x.lower != y.lower || x.upper != y.upper ||
        x.role != y.role) {
      return false;
    }
  }
  return true;
}

// The same values as held-out runs see them: the per-experiment ones aside, which every
// held-out run replaces (by its own estimate, or their start).
bool SameValues(const HeldOutRequest& a, const HeldOutRequest& b) {
  if (a.values.size() != b.values.size()) return false;
  const ModelInfo& info = a.model->info();
  for (size_t i = 0; i < a.values.size(); ++i) {
    bool replaced = false;
    for (const ParameterSpec& spec : a.per_run.parameters)
      replaced |= spec.name == info.parameters[i];
    if (!replaced && a.values[i] != b.values[i]) return false;
  }
  return true;
}

// Whether `part` lists some of `whole`'s records in the same order.
bool InOrderSubset(const std::vector<std::string>& part, const std::vector<std::string>& whole) {
  size_t k = 0;
  for (const std::string& name : whole) {
    if (k < part.size() && part[k] == name) ++k;
  }
  return !part.empty() && k == part.size();
}

}  // namespace

bool HeldOutMemo::Find(const HeldOutRequest& request, HeldOutAnswer* answer) const {
  for (auto entry = entries_.rbegin(); entry != entries_.rend(); ++entry) {
    const auto& [asked, given] = *entry;
    if (asked.model != request.model || (request.parameters && !asked.parameters) ||
        (request.residuals && !asked.residuals) || asked.free_states != request.free_states ||
        !InOrderSubset(request.names, asked.names) || !SameSettings(asked, request) ||
        !SamePerRun(asked.per_run, request.per_run) || !SameStart(asked.start, request.start) ||
        !SameValues(asked, request)) {
      continue;
    }
    const std::vector<std::string>& names = request.names;
    auto taken = [&](const std::string& experiment) {
      return std::find(names.begin(), names.end(), RecordName(experiment)) != names.end();
    };
    *answer = HeldOutAnswer();
    for (const ExperimentFit& fit : given.fits) {
      if (taken(fit.experiment)) answer->fits.push_back(fit);
    }
    if (request.parameters) {
      HeldOutParameters& held = answer->parameters;
      held.fitted = given.parameters.fitted;
      held.parameters = given.parameters.parameters;
      for (const Estimate& e : given.parameters.estimates) {
        if (taken(e.experiment)) held.estimates.push_back(e);
      }
      for (const ExperimentFit& fit : given.parameters.without) {
        if (taken(fit.experiment)) held.without.push_back(fit);
      }
    }
    if (request.residuals) {
      for (const ResidualAnalysis& a : given.residuals) {
        if (taken(a.experiment)) answer->residuals.push_back(a);
      }
    }
    return true;
  }
  return false;
}

bool HeldOutMemo::Fit(const RunConfig& config, const std::vector<HeldOutRequest>& requests,
                      TrajectoryCache* cache, std::vector<HeldOutAnswer>* answers,
                      std::string* error) {
  answers->assign(requests.size(), HeldOutAnswer());
  std::vector<size_t> fitted;
  std::vector<HeldOutPass> passes;
  for (size_t k = 0; k < requests.size(); ++k) {
    if (Find(requests[k], &(*answers)[k])) continue;
    HeldOutAnswer& a = (*answers)[k];
    fitted.push_back(k);
    passes.push_back({&requests[k].values, &a.fits,
                      requests[k].parameters ? &a.parameters : nullptr,
                      requests[k].residuals ? &a.residuals : nullptr});
  }
  if (passes.empty()) return true;
  const HeldOutRequest& first = requests[fitted.front()];
  if (!SimulateHeldOutPasses(config, *first.model, first.names, first.options, first.free_states,
                             first.local, passes, cache, error, first.per_run, first.start)) {
    return false;
  }
  for (size_t k : fitted) entries_.emplace_back(requests[k], (*answers)[k]);
  return true;
}

}  // namespace vesselid
