// The smallest complete use of the engine: simulate a 20/20 zigzag of a first-order Nomoto
// vessel with 0.1 deg heading noise, then identify T and K by output error from a poor start
// and print them with their standard errors.
#include <cstdio>

#include "engine/vesselid.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/nomoto_models.h"

int main() {
  using namespace vesselid;
  auto model = MakeModelHandle(nomoto::FirstOrder());
  const double kDeg = M_PI / 180.0;

  nomoto::ClosedLoopOptions zigzag;  // steering gear Tm = 1 s, 0.02 s sampling
  zigzag.duration = 300.0;
  zigzag.excitation.type = nomoto::Excitation::Type::kZigzag;
  zigzag.excitation.zigzag_rudder = 20 * kDeg;
  zigzag.excitation.zigzag_heading = 20 * kDeg;
  zigzag.heading_noise = 0.1 * kDeg;
  Trajectory data;
  std::string error;
  if (!nomoto::SimulateClosedLoop(*model, {8.0, 0.12, 0.0}, zigzag, &data, &error)) return 1;

  ExperimentSpec spec;  // what a config's `experiments` entry says
  spec.name = "zigzag";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  Experiment experiment;
  if (!BuildExperiment(spec, data, model->info(), {}, &experiment, &error)) return 1;

  ParameterSpec t{"T", 30.0, 0.5, 200.0}, k{"K", 0.5, 0.001, 2.0};
  OutputErrorOptions options;
  options.free_initial_states = {"psi"};
  auto problem = OutputErrorProblem::Create(model.get(), {experiment}, {t, k}, options, &error);
  StageSummary summary;
  if (!problem || !RunStage(StageOptions(), problem.get(), &summary)) return 1;

  std::printf("%s\n", summary.BriefReport().c_str());
  for (int i = 0; i < 2; ++i) {
    std::printf("%s = %.4f +- %.4f (truth %.2f)\n", problem->variables()[i].name.c_str(),
                problem->variables()[i].value(), summary.uncertainty.StdError(i),
                i == 0 ? 8.0 : 0.12);
  }
  return 0;
}
