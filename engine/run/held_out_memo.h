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
#include "engine/run/run_result.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

// What a held-out pass fits (SimulateHeldOutPasses' arguments for one pass).
struct HeldOutRequest {
  const ModelHandle* model = nullptr;
  std::vector<std::string> names;  // records
  ExperimentOptions options;
  std::vector<std::string> free_states;
  LocalSolveOptions local;
  HeldOutPerRun per_run;
  std::vector<double> values;  // model order
};

// What it gave: the fits; with `with_parameters`, the per-experiment estimates and the fits
// without them; with `with_residuals`, the fits' residual analyses.
struct HeldOutAnswer {
  std::vector<ExperimentFit> fits;
  HeldOutParameters parameters;
  std::vector<ResidualAnalysis> residuals;
  bool with_parameters = false, with_residuals = false;
};

class HeldOutMemo {
 public:
  // A remembered answer holding `request` (same model, settings, free states and
  // per-experiment treatment, the same values but for the per-experiment ones, which every
  // held-out run replaces, and its records among the remembered ones, in the same order),
  // with what `need_parameters` and `need_residuals` ask for: its part for request.names
  // into *answer; false if none.
  bool Find(const HeldOutRequest& request, bool need_parameters, bool need_residuals,
            HeldOutAnswer* answer) const;
  void Remember(HeldOutRequest request, HeldOutAnswer answer);

 private:
  std::vector<std::pair<HeldOutRequest, HeldOutAnswer>> entries_;
};

}  // namespace vesselid
