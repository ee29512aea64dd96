#include "engine/solve/start_failure.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "engine/solve/metrics.h"

namespace vesselid {
namespace {

// "experiment 'run', output psi at t = 12.3 s" for residual `row` of experiment e's block.
std::string SampleName(const OutputErrorProblem& problem, int e, int row) {
  const Experiment& experiment = problem.experiments()[e];
  int node = 0;
  while (node + 1 < experiment.num_nodes() && experiment.node_first_sample[node + 1] <= row) {
    ++node;
  }
  char text[300];
  std::snprintf(text, sizeof(text), "experiment '%s', output %s at t = %g s",
                experiment.name.c_str(),
                problem.model().info().outputs[experiment.samples[row].output].c_str(),
                experiment.node_time[node]);
  return text;
}

// Every simulation runs: the first residual, or derivative of a residual by a free variable,
// that is not finite. (An experiment's cost refuses a non-finite derivative, so each free
// variable's derivatives are evaluated alone to name it.)
std::string NonFiniteDerivative(OutputErrorProblem& problem) {
  ceres::Problem& ceres_problem = *problem.problem();
  std::map<const double*, const Variable*> variable_of;
  for (const Variable& v : problem.variables()) variable_of[v.block] = &v;
  const std::vector<ceres::ResidualBlockId>& blocks = problem.data_residual_blocks();
  for (size_t e = 0; e < blocks.size(); ++e) {
    const int rows = problem.experiments()[e].num_samples();
    std::vector<double> residuals(rows);
    double cost = 0.0;
    const std::string experiment = "experiment '" + problem.experiments()[e].name + "'";
    if (!ceres_problem.EvaluateResidualBlock(blocks[e], false, &cost, residuals.data(),
                                              nullptr)) {
      return experiment + ": its residuals cannot be evaluated";
    }
    for (int r = 0; r < rows; ++r) {
      if (!std::isfinite(residuals[r])) {
        return SampleName(problem, static_cast<int>(e), r) + ": the residual is not finite";
      }
    }
    std::vector<double*> parameters;
    ceres_problem.GetParameterBlocksForResidualBlock(blocks[e], &parameters);
    for (size_t j = 0; j < parameters.size(); ++j) {
      if (ceres_problem.IsParameterBlockConstant(parameters[j])) continue;
      const int size = ceres_problem.ParameterBlockSize(parameters[j]);
      std::vector<double> jacobian(static_cast<size_t>(rows) * size, 0.0);
      std::vector<double*> jacobians(parameters.size(), nullptr);
      jacobians[j] = jacobian.data();
      const bool evaluated = ceres_problem.EvaluateResidualBlock(
          blocks[e], false, &cost, residuals.data(), jacobians.data());
      int row = -1;
      for (size_t i = 0; evaluated && i < jacobian.size() && row < 0; ++i) {
        if (!std::isfinite(jacobian[i])) row = static_cast<int>(i) / size;
      }
      if (evaluated && row < 0) continue;
      const auto v = variable_of.find(parameters[j]);
      const std::string variable = v == variable_of.end() ? "a variable" : v->second->name;
      return (row >= 0 ? SampleName(problem, static_cast<int>(e), row) : experiment) +
             ": its derivative by " + variable + " is not finite";
    }
  }
  return "";
}

}  // namespace

std::string StartFailure(OutputErrorProblem* problem_ptr) {
  OutputErrorProblem& problem = *problem_ptr;
  const ModelInfo& info = problem.model().info();
  const int ny = static_cast<int>(info.outputs.size());
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& experiment = problem.experiments()[e];
    const std::vector<double> p = problem.ParametersOf(static_cast<int>(e));
    const std::vector<double> x0 = problem.InitialStateOf(static_cast<int>(e));
    const std::vector<double> c = problem.InputCorrectionsOf(static_cast<int>(e));
    std::vector<double> outputs;
    if (problem.model().SimulateOutputs(experiment, p.data(), x0.data(), &outputs,
                                        c.empty() ? nullptr : c.data())) {
      continue;
    }
    std::string text =
        "the simulation diverges at the start values: " + DivergenceMessage(experiment, outputs, ny);
    char part[200];
    for (size_t s = 0; s < x0.size(); ++s) {
      if (std::isfinite(x0[s])) continue;
      std::snprintf(part, sizeof(part), "; its initial state %s is %g", info.states[s].c_str(),
                    x0[s]);
      text += part;
    }
    // The first node with a non-finite output, and the step into it.
    size_t step = 0;
    for (int k = 0; k + 1 < experiment.num_nodes(); ++k) {
      const size_t next = static_cast<size_t>(k + 1) * ny;
      if (next + ny > outputs.size()) break;
      std::string bad;
      for (int c = 0; c < ny; ++c) {
        if (!std::isfinite(outputs[next + c])) bad += (bad.empty() ? "" : ", ") + info.outputs[c];
      }
      if (bad.empty()) {
        step += experiment.node_substeps[k];
        continue;
      }
      std::snprintf(part, sizeof(part),
                    "; %s not finite at t = %g s (inputs at t = %g s:", bad.c_str(),
                    experiment.node_time[k + 1], experiment.node_time[k]);
      text += part;
      const int nu = experiment.num_inputs;
      const char* separator = "";
      for (int i = 0; i < nu; ++i) {
        const double u = experiment.input_cache[3 * step * nu + i];
        if (std::isnan(u) && info.InputOptional(i)) continue;  // not recorded
        std::snprintf(part, sizeof(part), "%s %s = %g", separator, info.inputs[i].c_str(), u);
        text += part;
        separator = ",";
      }
      text += ")";
      break;
    }
    const std::vector<std::string> broken = problem.model().Admissibility(p.data());
    for (const std::string& condition : broken) text += "; at these values " + condition;
    return text;
  }
  const std::string derivative = NonFiniteDerivative(problem);
  return derivative.empty() ? "" : "at the start values, " + derivative;
}


}  // namespace vesselid
