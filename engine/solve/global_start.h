// Global start: an NLopt global algorithm searches the box of the bounded free variables
// (normalised to [0, 1]) on the output-error cost; the best distinct points it visited are
// returned as candidates for local refinement. A diverging simulation scores a large
// penalty instead of failing the search.
#pragma once

#include <string>
#include <vector>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/progress.h"

namespace vesselid {

struct GlobalStartOptions {
  // NLopt algorithm name, e.g. GN_DIRECT_L, GN_CRS2_LM, GN_ISRES, GN_ESCH, GN_MLSL_LDS.
  std::string algorithm = "GN_CRS2_LM";
  int max_evaluations = 1000;
  double max_time_seconds = 600.0;
  unsigned seed = 1;
  int population = 0;            // 0: NLopt's default
  int candidates = 3;            // best distinct points handed to local refinement
  double min_separation = 0.05;  // between candidates, in normalised coordinates (max-norm)
  ProgressCallback progress;     // after each evaluation; may be empty

  bool IsValid(std::string* error) const;
};

struct GlobalStartSummary {
  bool run = false;
  std::vector<std::string> variables;  // names of the searched variables
  int evaluations = 0;
  int failed_evaluations = 0;  // diverging simulations
  double best_cost = -1.0;
  double time_seconds = 0.0;
  std::string result;  // NLopt's return code
  std::string message;
  // Full value vectors (as OutputErrorProblem::Values) of the candidates, best first.
  std::vector<std::vector<double>> candidates;
  std::vector<double> candidate_costs;
  // Best finite cost after each evaluation (NaN until one is finite).
  std::vector<double> best_cost_history;

  std::string BriefReport() const;
};

// Searches from the problem's current values (unsearched variables keep them); restores the
// values before returning. False with a message if nothing can be searched.
bool RunGlobalStart(const GlobalStartOptions& options, OutputErrorProblem* problem,
                    GlobalStartSummary* summary);

}  // namespace vesselid
