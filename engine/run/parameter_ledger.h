// What a staged run knows of each parameter as its stages finish (seed 002's bookkeeping):
// the latest estimate, which starts later stages and holds the parameters they do not list,
// and every estimate with its stage, standard error and role, from which the final values
// are made: isolated and free parameters from the last stage that estimated them, shared
// ones fused over all their stage estimates (fusion.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/model/model.h"
#include "engine/run/fusion.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/parameter.h"

namespace vesselid {

struct ParameterLedger {
  struct Entry {
    std::string stage;
    double value;
    double std_error;  // NaN when undetermined
    ParameterRole role;
  };
  std::map<std::string, double> latest;
  // Bounds of the latest estimate: a later stage that lists the parameter without a bound
  // keeps that bound (a refinement must not lose what kept an earlier stage physical).
  std::map<std::string, std::pair<double, double>> bounds;
  std::map<std::string, std::vector<Entry>> estimates;
  // Latest per-experiment estimates: parameter -> experiment -> value. A later stage listing
  // the parameter as per_experiment without a start starts each experiment from its own.
  std::map<std::string, std::map<std::string, double>> per_experiment;
};

// Full parameter list of a stage: starts resolved from the ledger, unlisted ones fixed there,
// bounds a listed one does not give taken from its latest estimate. False when a carried
// start falls outside the stage's bounds.
bool ResolveParameters(const StageConfig& stage, const ModelInfo& info,
                       const ParameterLedger& ledger, std::vector<ParameterSpec>* specs,
                       std::string* error);

// Enters a finished stage's estimates of parameters estimated once (free, isolated, shared),
// and its per-experiment estimates as the latest of their experiments.
void RecordStage(const StageResult& stage, ParameterLedger* ledger);

// Enters the start values of a stage set aside (StageResult::rejected) as the latest values of
// its parameters: later stages and the final values take them, as the rejection says, not the
// model's defaults where no kept stage estimated them.
void RecordStartValues(const StageResult& stage, ParameterLedger* ledger);

// A kept stage's estimates (RecordStage); a stage set aside against its start, its start values
// (RecordStartValues); one set aside against the previous stages' values (HeldOutCheck::
// baseline), nothing: the ledger holds those.
void RecordStageOrItsBaseline(const StageResult& stage, ParameterLedger* ledger);

// Every model parameter's final value under `rule` (information: the shared parameters
// fused jointly with each stage's covariance block, per parameter when that is singular).
std::vector<FinalParameter> FinalParameters(const ModelInfo& info, const ParameterLedger& ledger,
                                            const std::vector<StageResult>& stages,
                                            FusionRule rule);

}  // namespace vesselid
