#include "engine/run/fusion.h"

#include <cmath>

namespace vesselid {

const char* FusionRuleToString(FusionRule rule) {
  switch (rule) {
    case FusionRule::kMean:
      return "mean";
    case FusionRule::kInformation:
      return "information";
    case FusionRule::kInverseVariance:
      break;
  }
  return "inverse_variance";
}

bool StringToFusionRule(const std::string& text, FusionRule* rule) {
  for (FusionRule r : {FusionRule::kInverseVariance, FusionRule::kMean, FusionRule::kInformation}) {
    if (text == FusionRuleToString(r)) {
      *rule = r;
      return true;
    }
  }
  return false;
}

void FuseEstimates(const std::vector<double>& values, const std::vector<double>& std_errors,
                   FusionRule rule, double* value, double* std_error, std::string* rule_used) {
  const size_t n = values.size();
  bool all_known = true;
  for (double s : std_errors) all_known = all_known && std::isfinite(s) && s > 0;
  if (rule != FusionRule::kMean && all_known) {
    double weights = 0.0, sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double w = 1.0 / (std_errors[i] * std_errors[i]);
      weights += w;
      sum += w * values[i];
    }
    *value = sum / weights;
    *std_error = 1.0 / std::sqrt(weights);
    *rule_used = "inverse_variance";
    return;
  }
  double sum = 0.0, variance = 0.0;
  for (size_t i = 0; i < n; ++i) {
    sum += values[i];
    variance += std_errors[i] * std_errors[i];
  }
  *value = sum / n;
  *std_error = std::sqrt(variance) / n;  // NaN if any stage left it undetermined
  *rule_used = rule == FusionRule::kMean ? "mean" : "mean (a stage has no standard error)";
}

bool FuseJointly(int n, const std::vector<SharedEstimate>& estimates, Eigen::VectorXd* value,
                 Eigen::MatrixXd* covariance) {
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd weighted = Eigen::VectorXd::Zero(n);
  for (const SharedEstimate& e : estimates) {
    const Eigen::LLT<Eigen::MatrixXd> llt(e.covariance);
    if (llt.info() != Eigen::Success) return false;
    const Eigen::MatrixXd inverse =
        llt.solve(Eigen::MatrixXd::Identity(e.covariance.rows(), e.covariance.cols()));
    const Eigen::VectorXd projected = inverse * e.value;
    const int m = static_cast<int>(e.parameters.size());
    for (int i = 0; i < m; ++i) {
      weighted[e.parameters[i]] += projected[i];
      for (int j = 0; j < m; ++j) information(e.parameters[i], e.parameters[j]) += inverse(i, j);
    }
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(information);
  if (llt.info() != Eigen::Success) return false;
  *covariance = llt.solve(Eigen::MatrixXd::Identity(n, n));
  *value = *covariance * weighted;
  return true;
}

}  // namespace vesselid
