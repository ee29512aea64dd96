#include "tests/models/model_factory.h"

#include <stdexcept>

namespace vesselid::testing {

const std::vector<ModelVariant>& ModelVariants() {
  static const std::vector<ModelVariant> variants = [] {
    std::vector<ModelVariant> v;
    AddNomotoVariants(&v);
    AddNomotoUnstableVariants(&v);
    AddInputGainVariants(&v);
    AddEriksenVariants(&v);
    AddErunsalVariants(&v);
    AddMmgVariants(&v);
    return v;
  }();
  return variants;
}

std::vector<double> JacobianPoint(const std::vector<double>& truth,
                                  const std::vector<double>& scales, double factor,
                                  double zero_offset, const std::vector<double>& state) {
  std::vector<double> theta;
  for (size_t i = 0; i < truth.size(); ++i) {
    theta.push_back((truth[i] * factor + (truth[i] == 0.0 ? zero_offset : 0.0)) / scales[i]);
  }
  theta.insert(theta.end(), state.begin(), state.end());
  return theta;
}

Experiment Build(const ExperimentSpec& spec, const Trajectory& data, const ModelInfo& info,
                 const ExperimentOptions& options) {
  Experiment e;
  std::string error;
  if (!BuildExperiment(spec, data, info, options, &e, &error)) throw std::runtime_error(error);
  return e;
}

Rk4Case MakeRk4Case(const ModelInfo& info, ExperimentSpec spec, Trajectory data,
                    double reference_step, std::array<double, 3> steps, double tolerance) {
  Rk4Case c;
  c.build = [info, spec = std::move(spec), data = std::move(data)](double max_step) {
    ExperimentOptions options;
    options.max_step = max_step;
    return Build(spec, data, info, options);
  };
  c.reference_step = reference_step;
  c.steps = steps;
  c.tolerance = tolerance;
  return c;
}

ParameterSpec PerturbedSpec(const std::string& name, double truth, int index, double perturbation) {
  ParameterSpec s;
  s.name = name;
  s.start = truth * (index % 2 == 0 ? 1.0 + perturbation : 1.0 - perturbation);
  return s;
}

}  // namespace vesselid::testing
