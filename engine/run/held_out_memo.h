// Held-out passes already fitted in a run, so that a pass asked again is taken rather than
// fitted again: a stage's start is often the previous stage's estimate (the same held-out
// fits), and the final validation is often the last stage's. Each held-out run is a problem
// of its own, so a pass over some of a remembered pass's records takes those records' fits.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/run/held_out.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

// What a held-out pass fits (SimulateHeldOutPasses' arguments for one pass), and whether it
// needs the per-experiment estimates with the fits without them, and the residual analyses.
struct HeldOutRequest {
  const ModelHandle* model = nullptr;
  std::vector<std::string> names;  // records
  ExperimentOptions options;
  std::vector<std::string> free_states;
  LocalSolveOptions local;
  HeldOutPerRun per_run;
  HeldOutStart start;
  std::vector<double> values;  // model order
  bool parameters = false, residuals = false;
};

// What it gave: the fits, and what the request needed.
struct HeldOutAnswer {
  std::vector<ExperimentFit> fits;
  HeldOutParameters parameters;
  std::vector<ResidualAnalysis> residuals;
};

class HeldOutMemo {
 public:
  // The answers to `requests`, passes over the same records with the same model, settings,
  // free states and per-experiment treatment at different values: each taken from a
  // remembered pass that holds it, the others fitted in one parallel batch
  // (SimulateHeldOutPasses) and remembered. False with `error` when the records cannot be
  // prepared.
  bool Fit(const RunConfig& config, const std::vector<HeldOutRequest>& requests,
           TrajectoryCache* cache, std::vector<HeldOutAnswer>* answers, std::string* error);

 private:
  // A remembered answer holding `request` (same model, settings, free states and
  // per-experiment treatment, the same values but for the per-experiment ones, which every
  // held-out run replaces, its records among the remembered ones in the same order, and what
  // it needs): its part for request.names into *answer; false if none.
  bool Find(const HeldOutRequest& request, HeldOutAnswer* answer) const;

  std::vector<std::pair<HeldOutRequest, HeldOutAnswer>> entries_;
};

}  // namespace vesselid
