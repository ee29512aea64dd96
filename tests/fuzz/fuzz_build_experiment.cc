// Fuzz target for BuildExperiment (engine/model/experiment.h) on what ReadTrajectoryCsv
// accepts: a first-order Nomoto experiment (input delta, output psi, an angle) over the data's
// whole time, with the step bound and the wrap chosen by the input's first byte. Any bytes
// give either an experiment that keeps its promises (increasing nodes, at least one positive
// finite step per interval, an input row per step point, finite samples and weights) or false
// with a message naming the experiment or the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/model/experiment.h"
#include "problems/nomoto/handles.h"
#include "tests/fuzz/fuzz_input_file.h"

// Undefined behaviour is a finding, not a warning: stop at the first report so that
// libFuzzer keeps the input.
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace vesselid;
  static const auto model = nomoto::MakeFirstOrderHandle();
  static fuzz::FuzzInputFile file("input.csv");
  const uint8_t choice = size > 0 ? data[0] : 0;
  const std::string& path = file.Write(size > 0 ? data + 1 : data, size > 0 ? size - 1 : 0);
  ExperimentSpec spec;
  spec.name = "run";
  spec.file = path;
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  if (choice & 1) spec.wrapped_outputs = {"psi"};
  if (choice & 2) spec.default_interpolation = Interpolation::kZeroOrderHold;
  spec.csv.max_values = 1'000'000;
  ExperimentOptions options;
  options.max_step = (choice & 4) ? 0.0 : 0.05 * ((choice >> 3) + 1);
  options.max_steps = 200'000;  // the run's limit, scaled to a fuzz iteration
  Trajectory trajectory;
  std::string error;
  if (!LoadExperimentData(spec, &trajectory, &error)) {
    FUZZ_CHECK(error.compare(0, path.size() + 1, path + ":") == 0);
    return 0;
  }
  Experiment e;
  if (!BuildExperiment(spec, trajectory, model->info(), options, &e, &error)) {
    FUZZ_CHECK(error.compare(0, 16, "experiment 'run'") == 0);
    return 0;
  }
  const int nodes = e.num_nodes();
  FUZZ_CHECK(nodes >= 2);
  FUZZ_CHECK(e.node_substeps.size() + 1 == static_cast<size_t>(nodes));
  size_t steps = 0;
  for (int k = 0; k + 1 < nodes; ++k) {
    FUZZ_CHECK(e.node_time[k + 1] > e.node_time[k]);
    FUZZ_CHECK(e.node_substeps[k] >= 1 && e.node_step[k] > 0.0 && std::isfinite(e.node_step[k]));
    steps += e.node_substeps[k];
  }
  FUZZ_CHECK(steps <= options.max_steps);
  FUZZ_CHECK(e.input_cache.size() == (3 * steps + 1) * static_cast<size_t>(e.num_inputs));
  FUZZ_CHECK(e.node_first_sample.size() == static_cast<size_t>(nodes) + 1);
  for (const ExperimentSample& s : e.samples) {
    FUZZ_CHECK(std::isfinite(s.value) && std::isfinite(s.weight) && s.weight >= 0.0);
    FUZZ_CHECK(std::abs(s.weight * s.value) <= kMaxDataMagnitude);
  }
  FUZZ_CHECK(e.initial_state.size() == model->info().states.size());
  return 0;
}
