#include "engine/run/experiment_residuals.h"

#include "engine/base/nan.h"

namespace vesselid {

bool SimulatedMinusMeasured(OutputErrorProblem* problem, int e, std::vector<double>* d) {
  const Experiment& experiment = problem->experiments()[e];
  std::vector<double> r(experiment.num_samples());
  double cost = 0.0;
  if (!problem->problem()->EvaluateResidualBlock(problem->data_residual_blocks()[e], false, &cost,
                                                 r.data(), nullptr)) {
    return false;
  }
  d->resize(r.size());
  for (size_t i = 0; i < r.size(); ++i) {
    const double w = experiment.samples[i].weight;
    (*d)[i] = w != 0.0 ? r[i] / w : kNaN;
  }
  return true;
}

}  // namespace vesselid
