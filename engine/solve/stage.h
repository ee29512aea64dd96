// One identification stage: optional NLopt global start, Ceres refinement of the start point
// and of every global candidate (the lowest final cost wins), ordering of exchangeable
// parameters, uncertainty, local analysis and fit metrics at the optimum.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/covariance.h"
#include "engine/solve/global_start.h"
#include "engine/solve/local_analysis.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/uncertainty_method.h"

namespace vesselid {

struct StageOptions {
  std::string name = "stage";
  bool use_global_start = false;
  GlobalStartOptions global;
  LocalSolveOptions local;
  bool compute_uncertainty = true;  // and the local analysis (local_analysis.h)
  UncertaintyOptions uncertainty;   // how, when computed
  // Before each refinement, solve for the free initial states alone with the parameters
  // held: a segment started from zero velocities would otherwise drag the parameters away.
  bool initial_states_first = true;

  bool IsValid(std::string* error) const;
};

struct StageSummary {
  std::string name;
  bool usable = false;
  std::string message;
  GlobalStartSummary global;
  // [0]: from the start point; then extra starts, then global candidates.
  std::vector<LocalSolveSummary> refinements;
  int chosen = -1;                             // index into refinements
  Uncertainty uncertainty;
  LocalAnalysis analysis;  // conditioning and sensitivities at the optimum
  std::vector<ExperimentFit> fits;
  std::vector<std::string> notes;     // what the solver did, in order (narrative)
  std::vector<Finding> findings;      // what it found doubtful (typed; diagnose/ adds the rest)
  double time_seconds = 0.0;

  const LocalSolveSummary& local() const { return refinements[chosen]; }
  std::string BriefReport() const;
};

// Refines the problem's current values, then each of `extra_starts` (full value vectors, as
// OutputErrorProblem::Values) and the global candidates; the lowest final cost wins.
bool RunStage(const StageOptions& options, OutputErrorProblem* problem, StageSummary* summary,
              const std::vector<std::vector<double>>& extra_starts = {});

}  // namespace vesselid
