// Every model variant the engine ships, with what the model battery needs to exercise it
// (model_battery_test.cc): the model, its true parameters, and three cases built on demand
// (the data are simulated only when a test runs):
//
//   jacobian:  one experiment and a point theta = [parameters / scales, initial state] away
//              from the truth, where the Jet Jacobian of the whole-experiment residual must
//              match central finite differences within `tolerance` of each column's largest
//              entry, with at least `min_columns` columns that the residual depends on;
//   rk4:       an experiment whose inputs are constant between samples, simulated from its
//              initial state with max_step = reference_step and with steps[0..2]; the
//              errors must shrink by 2^4 per halving (log2 ratio within `tolerance` of 4);
//   recovery:  noisy experiments and a perturbed start; every free parameter must end within
//              `sigmas` reported standard errors of the truth (and, when set, with a standard
//              error below max_relative_std_error of it), and the residual SD must estimate
//              the weighted noise.
//
// A new family passes the battery by adding its variants here (one Add... function in its own
// variants_<family>.cc, listed in ModelVariants()); problems/README.md has the checklist.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "engine/vesselid.h"

namespace vesselid::testing {

struct JacobianCase {
  Experiment experiment;
  std::vector<double> scales;  // parameter scales of the cost (a non-unit one is checked)
  std::vector<double> theta;   // scaled parameters, then the initial state
  double tolerance = 1e-6;
  int min_columns = 0;
};

struct Rk4Case {
  std::function<Experiment(double max_step)> build;  // initial state set by the spec
  double reference_step = 0.0;
  std::array<double, 3> steps = {};  // each half the one before
  double tolerance = 0.35;
};

struct RecoveryCase {
  std::vector<Experiment> experiments;
  std::vector<ParameterSpec> specs;
  OutputErrorOptions options;
  int free_parameters = 0;              // how many the specs estimate (checked)
  double sigmas = 3.0;                  // |estimate - truth| < sigmas * standard error
  double max_relative_std_error = 0.0;  // > 0: standard error < this * max(|truth|, 0.01)
  // > 0: sqrt(residual variance / residual_weight) within residual_tolerance (relative) of
  // residual_sd, the noise SD in weighted residual units; residual_weight is the squared
  // length weight of the experiment (1 / samples).
  double residual_sd = 0.0;
  double residual_weight = 1.0;
  double residual_tolerance = 0.05;
};

struct ModelVariant {
  std::string name;  // test name suffix: letters, digits and underscores
  std::function<std::unique_ptr<ModelHandle>()> make;
  std::vector<double> truth;
  std::function<JacobianCase(const ModelHandle& model, const std::vector<double>& truth)> jacobian;
  std::function<Rk4Case(const ModelHandle& model)> rk4;
  std::function<RecoveryCase(const ModelHandle& model, const std::vector<double>& truth)> recovery;
};

// gtest prints a variant by its name.
inline void PrintTo(const ModelVariant& variant, std::ostream* out) { *out << variant.name; }

// Every variant: Nomoto (first order, second order, Norrbin; course-unstable n1-forms, with
// and without the speed input, and the second-order rates form), input gain (static, dynamic),
// Eriksen-Breivik 2-DOF, Erunsal 6-DOF under its DOF restrictions, MMG 3-DOF (KVLCC2).
const std::vector<ModelVariant>& ModelVariants();

// Each family's variants (variants_<family>.cc).
void AddNomotoVariants(std::vector<ModelVariant>* variants);
void AddNomotoUnstableVariants(std::vector<ModelVariant>* variants);
void AddInputGainVariants(std::vector<ModelVariant>* variants);
void AddEriksenVariants(std::vector<ModelVariant>* variants);
void AddErunsalVariants(std::vector<ModelVariant>* variants);
void AddMmgVariants(std::vector<ModelVariant>* variants);

// Shared helpers of the variant files.
// theta_i = (truth_i * factor, or zero_offset where truth_i is 0) / scale_i, then `state`.
std::vector<double> JacobianPoint(const std::vector<double>& truth,
                                  const std::vector<double>& scales, double factor,
                                  double zero_offset, const std::vector<double>& state);
// Builds `spec` on `data` for the model; throws std::runtime_error with the message.
Experiment Build(const ExperimentSpec& spec, const Trajectory& data, const ModelInfo& info,
                 const ExperimentOptions& options = {});
// The RK4 case of `spec` on `data`: built with each max_step, the reference and three steps.
Rk4Case MakeRk4Case(const ModelInfo& info, ExperimentSpec spec, Trajectory data,
                    double reference_step, std::array<double, 3> steps, double tolerance);
// Free parameter specs started at truth * (1 + perturbation), the sign alternating by index.
ParameterSpec PerturbedSpec(const std::string& name, double truth, int index, double perturbation);

}  // namespace vesselid::testing
