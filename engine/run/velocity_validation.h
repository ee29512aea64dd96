// Velocity metrics of held-out records for a model with an equation-error form (seed 000's
// validation, and the harder one):
//   one-step: x(k+1) predicted from the data's state at k (least_squares.h, OneStepMetrics);
//   free-run: each record simulated whole from the data's state at its first grid sample
//             (internal states as the model reconstructs them from the inputs), the
//             regressed states compared with the data's at every grid sample.
// "The data's state" is the Savitzky-Golay reconstruction of regression_data.h.
#pragma once

#include <string>
#include <vector>

#include "engine/regression/least_squares.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"

namespace vesselid {

// Metrics per experiment and regressed state over every sample (whatever regions a stage was
// fitted on), labelled "<experiment> one-step" and "<experiment> free-run". A record whose
// free run diverges is left out of the free-run metrics with a line in `diverged`. The records
// are measured on `threads` (0: the machine's cores) with the same results on any number.
// What the free runs' integration step follows (integration_step.h, kVelocityValidation):
// the configured `integration.max_step` and the stages whose values are validated.
struct VelocitySteps {
  double configured = 0.0;
  std::vector<const StageResult*> stages;
};

bool ValidateVelocities(const RunConfig& config, const ModelHandle& model,
                        const std::vector<std::string>& names, const RegressionDataOptions& data,
                        const std::vector<double>& p, TrajectoryCache* cache,
                        const VelocitySteps& steps, std::vector<ChannelMetrics>* metrics,
                        std::vector<std::string>* diverged, std::string* error,
                        int threads = 0, const HeldOutParameters* own = nullptr);

// `p` with each per-experiment parameter that `own` estimated for record `record` (a held-out
// run's own rudder bias, on its burn-in) at that estimate: a run's free run is simulated with
// the values its held-out fit had, not the training runs' mean.
std::vector<double> WithOwnValues(const ModelInfo& info, const std::vector<double>& p,
                                  const HeldOutParameters* own, const std::string& record);

// Free-run part on prepared records (which get the model's internal states at p).
bool FreeRunMetrics(const RunConfig& config, const ModelHandle& model, const std::vector<double>& p,
                    const TrajectoryCache& cache, const VelocitySteps& steps,
                    std::vector<RegressionRecord>* records, std::vector<ChannelMetrics>* metrics,
                    std::vector<std::string>* diverged, std::string* error);

}  // namespace vesselid
