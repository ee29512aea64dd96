// Residual analysis (residual_analysis.h) of a simulation fit: per experiment and compared
// output, the residuals e = simulated - measured at the channel's own sample times (an angle
// wrapped to (-pi, pi] where the experiment compares it so, as the fit does) against each
// model input as the experiment feeds the simulation (its input cache at the sample nodes).
#pragma once

#include <vector>

#include "engine/model/experiment.h"
#include "engine/model/model.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

// The inputs an experiment feeds its simulation at each node: the input cache's row at the
// start of the node's first RK4 step (three rows per step), the last row at the last node and
// past it.
class NodeInputs {
 public:
  explicit NodeInputs(const Experiment& experiment);
  size_t count() const { return num_inputs_; }
  // Appends each input's value at node k to (*inputs)[u] (inputs sized count()).
  void Append(size_t k, std::vector<std::vector<double>>* inputs) const;

 private:
  const Experiment& experiment_;
  size_t num_inputs_ = 0, cache_rows_ = 0;
  std::vector<size_t> rows_;  // per node
};

// fits[i] is matched to the experiment of the same name; diverged fits and experiments
// without a fit are left out.
std::vector<ResidualAnalysis> AnalyseFitResiduals(const ModelInfo& info,
                                                  const std::vector<Experiment>& experiments,
                                                  const std::vector<ExperimentFit>& fits);

// The same of a filter-error problem's normalised innovations nu / sqrt(S) at its current values
// (a correct model and disturbance make them white, uncorrelated with the inputs); empty for an
// output-error problem. Each analysis is marked `innovations`.
std::vector<ResidualAnalysis> AnalyseInnovations(const OutputErrorProblem& problem);

}  // namespace vesselid
