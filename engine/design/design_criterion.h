// The criteria a plan is chosen by, on the total information M = I_0 + I_plan of the
// relative parameters p_i / s_i (s_i: the parameter's magnitude), so that parameters of any
// unit weigh alike:
//   D: -log det(M + eps 1)       A: trace((M + eps 1)^-1)
//   E: -lambda_min(M)            parameter j: ((M + eps 1)^-1)_jj
// (lower is better; eps = 1e-9 max_i M_ii keeps a direction no experiment has yet
// determined finite and the plan that determines it far better).
#pragma once

#include <vector>

#include "Eigen/Core"
#include "engine/design/design_options.h"

namespace vesselid {

double CriterionValue(const Eigen::MatrixXd& relative_information, DesignCriterion criterion,
                      int parameter);

// Standard errors from the information of the parameters in their own units, the
// pseudo-inverse's; +infinity for a parameter on a direction with eigenvalue below 1e-12 of
// the largest (relative, `scale`), as the engine reports "undetermined".
std::vector<double> PredictedStdErrors(const Eigen::MatrixXd& information,
                                       const std::vector<double>& scale);

// The information of a covariance over the determined subspace (its pseudo-inverse).
Eigen::MatrixXd InformationOfCovariance(const Eigen::MatrixXd& covariance);

}  // namespace vesselid
