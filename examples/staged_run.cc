// A staged run assembled in C++, no YAML: a least-squares start refined by output error.
// Three zigzags of a first-order Nomoto vessel are recorded in memory, as a program holding a
// logger's arrays would pass them (rudder and heading with noise, yaw rate from a gyro): an
// experiment takes its record as a table (ExperimentSpec::table) instead of a file. Stage 1 regresses the yaw
// equation r' = K/T delta + K delta_0/T - 1/T r on Savitzky-Golay derivatives; stage 2 takes
// its estimates as starts and fits the heading by output error; a held-out 10/10 zigzag is
// simulated with the final values. Prints the run's text report.
#include <cstdio>
#include <iostream>
#include <memory>

#include "engine/vesselid.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

int main() {
  using namespace vesselid;
  const double kDeg = M_PI / 180.0;

  // The recorded experiments: zigzags rudder/heading 20/20, 30/30 and (held out) 10/10.
  std::shared_ptr<const ModelHandle> model = nomoto::MakeFirstOrderHandle();
  RunConfig config;
  config.model = model;
  config.family = "nomoto";
  const double zigzags[3] = {20.0, 30.0, 10.0};
  for (int i = 0; i < 3; ++i) {
    nomoto::ClosedLoopOptions zigzag;
    zigzag.duration = 300.0;
    zigzag.excitation.type = nomoto::Excitation::Type::kZigzag;
    zigzag.excitation.zigzag_rudder = zigzags[i] * kDeg;
    zigzag.excitation.zigzag_heading = zigzags[i] * kDeg;
    zigzag.heading_noise = 0.1 * kDeg;
    zigzag.rudder_noise = 0.1 * kDeg;
    zigzag.seed = i + 1;
    auto data = std::make_shared<Trajectory>();
    std::string error;
    ExperimentSpec spec;
    spec.name = "zigzag" + std::to_string(static_cast<int>(zigzags[i]));
    if (!nomoto::SimulateClosedLoop(*model, {8.0, 0.12, 0.002}, zigzag, data.get(), &error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    data->source = "experiment '" + spec.name + "' (in memory)";
    spec.table = data;  // t, delta, psi, r: the columns mapped below
    spec.inputs = {{"delta", "delta"}};
    spec.outputs = {{"psi", "psi"}, {"r", "r"}};
    config.experiments.push_back(spec);
  }

  // Stage 1: least squares on the yaw equation, every parameter from the model default.
  StageConfig least_squares;
  least_squares.kind = StageConfig::Kind::kLeastSquares;
  least_squares.options.name = "least_squares";
  least_squares.experiments = {"zigzag20", "zigzag30"};
  least_squares.validation = {"zigzag10"};
  for (const char* name : {"T", "K", "delta_0"}) {
    ParameterSpec p;
    p.name = name;
    p.start_from_previous = true;  // the model default (no earlier stage)
    least_squares.parameters.push_back(p);
  }
  least_squares.parameters[0].lower = 0.5;
  least_squares.parameters[0].upper = 100.0;

  // Stage 2: output error on the heading from the least-squares estimates.
  StageConfig refinement = least_squares;
  refinement.kind = StageConfig::Kind::kOutputError;
  refinement.options.name = "output_error";
  refinement.experiment.outputs = {"psi"};
  refinement.problem.free_initial_states = {"psi", "r"};
  config.stages = {least_squares, refinement};

  config.has_final_validation = true;
  config.final_validation.experiments = {"zigzag10"};
  config.final_validation.experiment.outputs = {"psi"};
  config.final_validation.free_initial_states = {"psi"};

  RunResult result;
  std::string error;
  if (!Identify(config, &result, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::cout << RunResultToText(config, result);
  return 0;
}
