#include "engine/design/planned_information.h"

#include <cmath>
#include <memory>

#include "Eigen/Dense"
#include "engine/model/experiment.h"

namespace vesselid {

bool PlannedInformation(const ModelHandle& model, const PlannedRecord& record,
                        const std::vector<double>& p, const std::vector<double>& x0,
                        const InformationSetup& setup, Eigen::MatrixXd* information,
                        std::string* error) {
  const ModelInfo& info = model.info();
  const int nu = static_cast<int>(info.inputs.size());
  const int ny = static_cast<int>(info.outputs.size());
  const int np = static_cast<int>(info.parameters.size());
  const int nx = static_cast<int>(info.states.size());
  // The record as a log: its inputs, and its predicted outputs as the measurements (the
  // residuals are zero; only their derivatives matter).
  auto table = std::make_shared<Trajectory>();
  table->source = "planned experiment";
  table->t = record.time;
  ExperimentSpec spec;
  spec.name = "planned";
  spec.default_interpolation = Interpolation::kLinear;
  ExperimentOptions options;
  options.normalize_by_length = false;
  options.max_step = setup.max_step;
  for (int i = 0; i < nu; ++i) {
    if (!std::isfinite(record.inputs(0, i))) continue;  // an optional input not planned
    table->names.push_back("u." + info.inputs[i]);
    table->columns.emplace_back(record.inputs.col(i).data(),
                                record.inputs.col(i).data() + record.inputs.rows());
    spec.inputs[info.inputs[i]] = table->names.back();
  }
  for (int j = 0; j < ny; ++j) {
    const double sigma = j < static_cast<int>(setup.sigma.size()) ? setup.sigma[j] : 0.0;
    if (!(sigma > 0.0 && std::isfinite(sigma))) continue;
    table->names.push_back("y." + info.outputs[j]);
    table->columns.emplace_back(record.outputs.col(j).data(),
                                record.outputs.col(j).data() + record.outputs.rows());
    spec.outputs[info.outputs[j]] = table->names.back();
    spec.output_weights[info.outputs[j]] = 1.0 / sigma;
    options.outputs.push_back(info.outputs[j]);
  }
  if (options.outputs.empty()) {
    *error = "the planned record has no measured output (design.noise)";
    return false;
  }
  for (int i = 0; i < nx; ++i) spec.initial_state[info.states[i]] = x0[i];
  spec.table = table;
  Experiment experiment;
  if (!BuildExperiment(spec, *table, info, options, &experiment, error)) return false;
  std::unique_ptr<ceres::CostFunction> cost(
      model.NewExperimentCost(&experiment, std::vector<double>(np, 1.0), nullptr));
  // Blocks: every parameter, then every initial state (experiment_cost.h), each of size 1.
  std::vector<double> values(p.begin(), p.end());
  values.insert(values.end(), x0.begin(), x0.end());
  std::vector<const double*> blocks(np + nx);
  for (int b = 0; b < np + nx; ++b) blocks[b] = &values[b];
  std::vector<int> columns = setup.parameters;
  const int shared = static_cast<int>(columns.size());
  columns.insert(columns.end(), setup.nuisance.begin(), setup.nuisance.end());
  for (int s : setup.free_states) columns.push_back(np + s);
  const int m = experiment.num_samples();
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(m, columns.size());
  std::vector<double*> jacobians(np + nx, nullptr);
  for (size_t c = 0; c < columns.size(); ++c) jacobians[columns[c]] = jacobian.col(c).data();
  std::vector<double> residuals(m);
  if (!cost->Evaluate(blocks.data(), residuals.data(), jacobians.data())) {
    *error = "the planned record's simulation diverges";
    return false;
  }
  const Eigen::MatrixXd full = jacobian.transpose() * jacobian;
  const int nuisance = static_cast<int>(columns.size()) - shared;
  if (nuisance == 0) {
    *information = full;
    return true;
  }
  const Eigen::MatrixXd inn = full.bottomRightCorner(nuisance, nuisance);
  const Eigen::MatrixXd ipn = full.topRightCorner(shared, nuisance);
  const Eigen::MatrixXd pinv = inn.completeOrthogonalDecomposition().pseudoInverse();
  *information = full.topLeftCorner(shared, shared) - ipn * pinv * ipn.transpose();
  *information = 0.5 * (*information + information->transpose());
  return true;
}

}  // namespace vesselid
