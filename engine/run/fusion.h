// How the stage estimates of shared parameters become their final values.
//
//   mean:             seed 002: plain average, standard error sqrt(sum s_i^2) / n
//   inverse_variance: per parameter, x = sum(x_i / s_i^2) / sum(1 / s_i^2),
//                     standard error 1 / sqrt(sum 1 / s_i^2)
//   information:      jointly over every shared parameter, with each stage's covariance
//                     block C_i of the shared parameters it estimated (selection P_i):
//                       I = sum P_i^T C_i^-1 P_i,  x = I^-1 sum P_i^T C_i^-1 x_i,  Cov = I^-1
//                     (the best linear unbiased combination of independent stage estimates;
//                     keeps the correlations within a stage, which per-parameter weighting
//                     breaks: strongly correlated estimates such as added mass and damping
//                     of one manoeuvre compensate each other only as a set)
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {

enum class FusionRule { kInverseVariance, kMean, kInformation };
const char* FusionRuleToString(FusionRule rule);
bool StringToFusionRule(const std::string& text, FusionRule* rule);

// Fuses stage estimates (value, standard error) of one shared parameter by the mean or by
// inverse variance. Inverse-variance weighting needs every standard error; without them it
// falls back to the mean and says so in `rule_used`.
void FuseEstimates(const std::vector<double>& values, const std::vector<double>& std_errors,
                   FusionRule rule, double* value, double* std_error, std::string* rule_used);

// One stage's estimate of some of the shared parameters.
struct SharedEstimate {
  std::vector<int> parameters;  // indices into the fused vector
  Eigen::VectorXd value;
  Eigen::MatrixXd covariance;
};

// Information fusion of n shared parameters. False (outputs untouched) if a stage's
// covariance is not positive definite or the summed information is singular (a parameter
// no stage determines).
bool FuseJointly(int n, const std::vector<SharedEstimate>& estimates, Eigen::VectorXd* value,
                 Eigen::MatrixXd* covariance);

}  // namespace vesselid
