// Global start: candidates for the stage's local refinement, found in the box of the bounded
// free variables. The default, "multistart" (multistart.h), runs short Ceres solves from
// low-discrepancy points in log/linear coordinates and clusters their end points; an NLopt
// global algorithm named instead (e.g. GN_CRS2_LM) searches the box normalised to [0, 1] on
// the output-error cost and returns its best distinct visited points, a diverging
// simulation scoring a large penalty.
#pragma once

#include <string>
#include <vector>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/progress.h"

namespace vesselid {

struct GlobalStartOptions {
  // "multistart", or an NLopt algorithm name, e.g. GN_DIRECT_L, GN_CRS2_LM, GN_ISRES.
  std::string algorithm = "multistart";
  // multistart: points screened by their cost, Ceres iterations of each short solve, threads
  // (0: the cores).
  int points = 32;
  int short_iterations = 4;
  int threads = 0;
  // NLopt: cost evaluations.
  int max_evaluations = 1000;
  double max_time_seconds = 600.0;
  unsigned seed = 1;
  int population = 0;            // 0: NLopt's default
  int candidates = 3;            // best distinct points handed to local refinement
  double min_separation = 0.05;  // between candidates, in the box's coordinates (max-norm)
  ProgressCallback progress;     // after each evaluation; may be empty
  // Optima the stage has already refined (full value vectors) and their costs: the
  // multistart does not hand back a candidate that lies within min_separation of one at no
  // lower cost (its refinement would end there).
  std::vector<std::vector<double>> known_optima;
  std::vector<double> known_costs;

  bool IsValid(std::string* error) const;
};

struct GlobalStartSummary {
  bool run = false;
  std::vector<std::string> variables;  // names of the searched variables
  // multistart: those searched around their start (one-sided or no bounds, search_box.h)
  std::vector<std::string> around_start;
  std::string algorithm;
  // Segment length (s) the search ran on (search_horizons.h); 0: the whole experiments.
  double horizon_seconds = 0.0;
  int evaluations = 0;         // NLopt: cost evaluations; multistart: points screened
  int failed_evaluations = 0;  // diverging simulations (multistart: points)
  int abandoned = 0;           // multistart: short solves abandoned as clearly worse
  int short_solves = 0;        // multistart: short solves started (from the best screened)
  int known_joined = 0;        // multistart: end points within reach of a known optimum
  int clusters = 0;            // multistart: distinct end points
  int short_iterations_total = 0;  // multistart: Ceres iterations of the short solves
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
