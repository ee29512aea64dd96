// The Fisher information a planned record carries about a model's parameters,
//   I = sum_k S_k^T Sigma^-1 S_k,   S_k = d y(t_k) / d (p, x0),   Sigma = diag(sigma_c^2),
// evaluated by the engine's own output-error cost (exact sensitivities on Jets through RK4,
// experiment_cost.h) on the record with residual weights 1 / sigma_c; the record's own
// unknowns (its free initial states and per-experiment parameters, estimated again from it)
// are then marginalised out (the Schur complement):
//   I_eff = I_pp - I_pn I_nn^+ I_np.
// This is the information an output-error identification of the record adds to the others'
// when every sample is weighted by its noise (normalize_by_length: false).
#pragma once

#include <string>
#include <vector>

#include "Eigen/Core"
#include "engine/design/planned_record.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct InformationSetup {
  std::vector<int> parameters;   // model parameter indices, the rows and columns of I_eff
  std::vector<int> nuisance;     // model parameter indices estimated per experiment
  std::vector<int> free_states;  // initial states estimated from the record
  std::vector<double> sigma;     // per model output; not finite or <= 0: not measured
  double max_step = 0.0;         // RK4 step bound (0: the sample interval)
};

// False (with a message) when the record cannot be simulated or has no measured output.
bool PlannedInformation(const ModelHandle& model, const PlannedRecord& record,
                        const std::vector<double>& p, const std::vector<double>& x0,
                        const InformationSetup& setup, Eigen::MatrixXd* information,
                        std::string* error);

}  // namespace vesselid
