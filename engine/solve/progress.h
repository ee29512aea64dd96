// Progress of a running solve, for the terminal: reported once per Ceres iteration or global
// evaluation, never from the integrator's per-step path.
#pragma once

#include <functional>

namespace vesselid {

struct SolveProgress {
  enum class Phase { kGlobal, kLocal };
  Phase phase = Phase::kLocal;
  int refinement = 0;   // local: which refinement of the stage (0: from the start point)
  int refinements = 1;  // local: how many the stage runs
  int iteration = 0;    // Ceres iteration, or evaluations so far in the global search
  double cost = 0.0;    // Ceres: the iteration's cost; global: the best finite cost so far
  double segment_length = 0.0;  // continuation phase: its segment length, s; 0: whole records
};

using ProgressCallback = std::function<void(const SolveProgress&)>;

}  // namespace vesselid
