#include "engine/run/integration_step.h"

#include <algorithm>

namespace vesselid {
namespace {

// The shortest step a re-refinement gave the stages (0: none was re-refined).
double ShortestReducedStep(const std::vector<const StageResult*>& stages) {
  double step = 0.0;
  for (const StageResult* s : stages) {
    if (s->integration_step > 0.0 && (step <= 0.0 || s->integration_step < step)) {
      step = s->integration_step;
    }
  }
  return step;
}

// The shorter of two step bounds, either 0 for none.
double Shorter(double a, double b) {
  if (a <= 0.0) return b;
  if (b <= 0.0) return a;
  return std::min(a, b);
}

}  // namespace

double IntegrationStep(StepUse use, double configured,
                       const std::vector<const StageResult*>& stages, double grid_interval) {
  switch (use) {
    case StepUse::kStageFit:
      return configured;
    case StepUse::kStageValidation:
    case StepUse::kFinalValidation:
      return Shorter(configured, ShortestReducedStep(stages));
    case StepUse::kVelocityValidation:
      return Shorter(grid_interval / 10.0, Shorter(configured, ShortestReducedStep(stages)));
  }
  return configured;
}

}  // namespace vesselid
