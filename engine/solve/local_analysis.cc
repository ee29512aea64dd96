#include "engine/solve/local_analysis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/check.h"
#include "engine/base/nan.h"

namespace vesselid {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Eigenvalues of an experiment's normalised I_ss below this fraction of its largest are
// dropped from the pseudo-inverse (rounding level: only truly undetermined local unknowns).
constexpr double kLocalRankTolerance = 1e-14;

// Where a Jacobian column (a free variable) goes: a shared parameter or an unknown local to
// one experiment.
struct Column {
  int shared = -1;      // position among the shared parameters
  int experiment = -1;  // else the experiment and the position among its unknowns
  int local = -1;
  double inverse_scale = 1.0;  // dr/dp = dr/dtheta / scale
};

// Pseudo-inverse of a symmetric positive semi-definite matrix, computed on its
// diagonal-normalised form.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& c) {
  Eigen::VectorXd d = c.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int i = 0; i < d.size(); ++i) d[i] = d[i] > 0 ? 1.0 / d[i] : 0.0;
  const Eigen::MatrixXd normalised = d.asDiagonal() * c * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normalised);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  const double cutoff = kLocalRankTolerance * std::max(lambda.maxCoeff(), 0.0);
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(lambda.size());
  for (int k = 0; k < lambda.size(); ++k) {
    if (lambda[k] > cutoff && lambda[k] > 0) inverse[k] = 1.0 / lambda[k];
  }
  const Eigen::MatrixXd& v = eigen.eigenvectors();
  return d.asDiagonal() * (v * inverse.asDiagonal() * v.transpose()) * d.asDiagonal();
}

// "T2 + 0.97 T3": the kept terms by decreasing normalised component (the leading one first).
std::string CombinationText(const std::vector<std::string>& names,
                            const std::vector<double>& coefficients,
                            const Eigen::VectorXd& components) {
  std::vector<int> order;
  for (size_t j = 0; j < names.size(); ++j) {
    if (coefficients[j] != 0.0) order.push_back(static_cast<int>(j));
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](int i, int j) { return std::abs(components[i]) > std::abs(components[j]); });
  std::string text;
  for (int j : order) {
    if (text.empty()) {
      text = names[j];  // coefficient 1
      continue;
    }
    char term[256];
    std::snprintf(term, sizeof(term), " %c %.3g %s", coefficients[j] < 0 ? '-' : '+',
                  std::abs(coefficients[j]), names[j].c_str());
    text += term;
  }
  return text;
}

// Sums over the samples of one output channel.
struct ChannelSums {
  int count = 0;
  double variation = 0.0;    // sum (y - experiment mean)^2, measured
  Eigen::VectorXd dy2, dr2;  // per shared parameter: sum (dy/dp)^2, sum (dr/dp)^2
};

// Adds the size of each channel of `experiment` about its mean (angles from the first sample)
// to `sums`.
void AddChannelVariation(const Experiment& experiment, std::vector<ChannelSums>* sums) {
  const size_t num_outputs = sums->size();
  std::vector<double> first(num_outputs, kNaN), sum(num_outputs, 0.0), sum2(num_outputs, 0.0);
  std::vector<int> count(num_outputs, 0);
  for (const ExperimentSample& sample : experiment.samples) {
    const int c = sample.output;
    if (std::isnan(first[c])) first[c] = sample.value;
    double y = sample.value;
    if (experiment.Wrapped(c)) y = WrapAngle(y - first[c]);
    sum[c] += y;
    sum2[c] += y * y;
    ++count[c];
  }
  for (size_t c = 0; c < num_outputs; ++c) {
    if (count[c] == 0) continue;
    (*sums)[c].count += count[c];
    (*sums)[c].variation += std::max(0.0, sum2[c] - sum[c] * sum[c] / count[c]);
  }
}

// The k-th eigen-direction `v` of the normalised information (eigenvalue ratio `ratio`) as a
// combination of the parameters led by its largest component; `s` the residual SD.
WeakDirection Direction(const LocalAnalysisOptions& options, const LocalAnalysis& a,
                        const Eigen::VectorXd& v, const Eigen::VectorXd& inverse_d, double ratio,
                        double s, int k) {
  const int ns = static_cast<int>(v.size());
  int lead = 0;
  v.cwiseAbs().maxCoeff(&lead);
  const double lead_step = v(lead) * inverse_d[lead];  // dp_lead per unit normalised step
  WeakDirection w;
  w.coefficients.assign(ns, 0.0);
  for (int i = 0; i < ns; ++i) {
    if (i == lead || std::abs(v(i)) >= options.min_component)
      w.coefficients[i] = v(i) * inverse_d[i] / lead_step;
  }
  w.combination = CombinationText(a.names, w.coefficients, v);
  w.eigenvalue_ratio = ratio;
  const double lambda = a.eigenvalues[k];
  w.std_dev_normalised = lambda > 0 ? s / std::sqrt(lambda) : kInf;
  w.std_dev = std::abs(lead_step) * w.std_dev_normalised;
  w.status = ratio < options.undetermined_ratio ? DirectionStatus::kUndetermined
             : ratio < options.poor_ratio       ? DirectionStatus::kPoorlyDetermined
                                                : DirectionStatus::kDetermined;
  return w;
}

}  // namespace

const char* DirectionStatusToString(DirectionStatus status) {
  switch (status) {
    case DirectionStatus::kUndetermined:
      return "undetermined";
    case DirectionStatus::kPoorlyDetermined:
      return "poorly determined";
    case DirectionStatus::kDetermined:
      return "determined";
  }
  return "unknown";
}

bool ComputeLocalAnalysis(const LocalAnalysisOptions& options, OutputErrorProblem* problem,
                          LocalAnalysis* a, const SolutionJacobian* shared) {
  *a = LocalAnalysis();
  const auto start_time = std::chrono::steady_clock::now();
  const std::vector<Variable>& variables = problem->variables();
  const std::vector<Experiment>& experiments = problem->experiments();
  const ModelInfo& info = problem->model().info();
  const int num_experiments = static_cast<int>(experiments.size());

  // Columns in free-variable order.
  std::vector<Column> columns;
  std::vector<int> locals(num_experiments, 0);
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (!v.free) continue;
    Column column;
    column.inverse_scale = 1.0 / v.scale;
    if (v.experiment < 0) {
      column.shared = static_cast<int>(a->parameters.size());
      a->parameters.push_back(static_cast<int>(i));
      a->names.push_back(v.name);
    } else {
      column.experiment = v.experiment;
      column.local = locals[v.experiment]++;
      ++a->profiled;
    }
    columns.push_back(column);
  }
  const int ns = static_cast<int>(a->parameters.size());
  a->num_free = static_cast<int>(columns.size());
  a->num_residuals = problem->num_residuals();
  if (ns == 0) {
    a->message = "no free shared parameters";
    return false;
  }
  if (a->num_residuals <= a->num_free) {
    a->message = "fewer residuals than free variables";
    return false;
  }
  SolutionJacobian evaluated;
  if (shared == nullptr) {
    if (!EvaluateSolutionJacobian(problem, options.num_threads, &evaluated)) {
      a->message = "the Jacobian could not be evaluated at the solution";
      return false;
    }
    shared = &evaluated;
  }
  // Only the data rows [0, num_residuals) are read below.
  const ceres::CRSMatrix& jacobian = shared->jacobian;
  VESSELID_CHECK(shared->data_rows == a->num_residuals && jacobian.num_cols == a->num_free);
  const double cost = shared->DataCost();
  // Under the filter-error method the cost is a likelihood, its own scale (s^2 = 1), and each
  // sample has two rows, the innovation's and its variance's (filter_error_cost.h).
  const bool likelihood = problem->filter_error();
  const int rows_per_sample = likelihood ? 2 : 1;
  a->residual_variance = likelihood ? 1.0 : 2.0 * cost / (a->num_residuals - a->num_free);
  const double s = std::sqrt(a->residual_variance);

  // Experiment by experiment (rows in residual-block order, i.e. experiment then sample):
  // the dense Jacobian of its rows over [shared, own unknowns], I_pp += J_p^T J_p and the
  // Schur term I_ps I_ss^+ I_sp subtracted; channel sums alongside.
  const int num_outputs = static_cast<int>(info.outputs.size());
  std::vector<ChannelSums> sums(num_outputs);
  for (ChannelSums& c : sums) {
    c.dy2 = Eigen::VectorXd::Zero(ns);
    c.dr2 = Eigen::VectorXd::Zero(ns);
  }
  Eigen::MatrixXd ipp = Eigen::MatrixXd::Zero(ns, ns);
  Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(ns, ns);
  int row = 0;
  for (int e = 0; e < num_experiments; ++e) {
    const Experiment& experiment = experiments[e];
    const int rows = experiment.num_samples() * rows_per_sample, width = ns + locals[e];
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(rows, width);
    for (int i = 0; i < rows; ++i, ++row) {
      const ExperimentSample& sample = experiment.samples[i / rows_per_sample];
      const bool own_row = i % rows_per_sample == 0;  // the sample's (innovation's) row
      ChannelSums& channel = sums[sample.output];
      for (int k = jacobian.rows[row]; k < jacobian.rows[row + 1]; ++k) {
        const Column& column = columns[jacobian.cols[k]];
        const double value = jacobian.values[k] * column.inverse_scale;
        if (column.shared >= 0) {
          j(i, column.shared) = value;
          if (!own_row) continue;
          channel.dr2[column.shared] += value * value;
          if (sample.weight != 0.0) {
            const double dy = value / sample.weight;
            channel.dy2[column.shared] += dy * dy;
          }
        } else {
          VESSELID_CHECK(column.experiment == e);
          j(i, ns + column.local) = value;
        }
      }
    }
    // J^T J as a rank update: unlike a general product, never split over OpenMP threads
    // (thousands of small products would wait on each other on a busy machine).
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(width, width);
    g.selfadjointView<Eigen::Lower>().rankUpdate(j.transpose());
    g = g.selfadjointView<Eigen::Lower>();
    ipp += g.topLeftCorner(ns, ns);
    if (locals[e] > 0) {
      const Eigen::MatrixXd b = g.topRightCorner(ns, locals[e]);
      schur += b * PseudoInverse(g.bottomRightCorner(locals[e], locals[e])) * b.transpose();
    }
    AddChannelVariation(experiment, &sums);
  }
  a->information = ipp - schur;
  a->information = 0.5 * (a->information + a->information.transpose()).eval();

  // Column-normalised information and its eigen-directions.
  Eigen::VectorXd d = ipp.diagonal().cwiseSqrt();
  for (int i = 0; i < ns; ++i) {
    if (!(d[i] > 0)) d[i] = 1.0;  // no influence at all: a zero eigenvalue along it
  }
  const Eigen::VectorXd inverse_d = d.cwiseInverse();
  const Eigen::MatrixXd normalised =
      inverse_d.asDiagonal() * a->information * inverse_d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normalised);
  a->eigenvalues = eigen.eigenvalues();
  const Eigen::MatrixXd& v = eigen.eigenvectors();
  const double lambda_max = std::max(a->eigenvalues[ns - 1], 0.0);
  const double lambda_min = a->eigenvalues[0];
  a->condition_number = lambda_min > 0 ? std::sqrt(lambda_max / lambda_min) : kInf;
  auto ratio_of = [&](int k) {
    return lambda_max > 0 ? std::max(a->eigenvalues[k], 0.0) / lambda_max : 0.0;
  };

  // Standard errors from the pseudo-inverse over the determined directions; parameters that
  // take part in an undetermined direction have none.
  Eigen::MatrixXd pseudo = Eigen::MatrixXd::Zero(ns, ns);
  std::vector<bool> undetermined(ns, false);
  for (int k = 0; k < ns; ++k) {
    if (ratio_of(k) >= options.undetermined_ratio) {
      pseudo += v.col(k) * v.col(k).transpose() / a->eigenvalues[k];
      continue;
    }
    for (int i = 0; i < ns; ++i)
      undetermined[i] = undetermined[i] || std::abs(v(i, k)) >= options.min_component;
  }
  for (int i = 0; i < ns; ++i) {
    a->std_errors.push_back(undetermined[i] ? kNaN
                                            : s * std::sqrt(std::max(0.0, pseudo(i, i))) / d[i]);
  }

  // Weak directions, weakest first.
  for (int k = 0; k < ns; ++k) {
    const double ratio = ratio_of(k);
    if (k > 0 && ratio >= options.poor_ratio) break;
    a->directions.push_back(Direction(options, *a, v.col(k), inverse_d, ratio, s, k));
  }

  // Sensitivities of the compared channels.
  std::vector<int> compared;
  for (int c = 0; c < num_outputs; ++c) {
    if (sums[c].count == 0) continue;
    compared.push_back(c);
    a->channels.push_back(info.outputs[c]);
  }
  a->sensitivity.resize(compared.size(), ns);
  a->noise_sensitivity.resize(compared.size(), ns);
  for (size_t r = 0; r < compared.size(); ++r) {
    const ChannelSums& c = sums[compared[r]];
    const double size = std::sqrt(c.variation / c.count);
    for (int i = 0; i < ns; ++i) {
      const double value = variables[a->parameters[i]].value();
      const double magnitude = value != 0.0 ? std::abs(value) : 1.0;
      a->sensitivity(r, i) = magnitude * std::sqrt(c.dy2[i] / c.count) / size;
      a->noise_sensitivity(r, i) = magnitude * std::sqrt(c.dr2[i] / c.count) / s;
    }
  }
  a->available = true;
  a->time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return true;
}

}  // namespace vesselid
