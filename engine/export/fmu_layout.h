// The variables of an exported model's FMU and their value references, one layout for
// modelDescription.xml and the FMU's runtime. Reals, in this order:
//   inputs            causality input, continuous (the model's inputs, SI units)
//   outputs           causality output (the model's outputs)
//   state outputs     causality output: each state that is not also an output, by its name
//   parameters        causality parameter, tunable (the run's values)
//   initial states    "<state>_0", causality parameter, fixed
//   max_step          causality parameter, fixed: the RK4 step bound (0: one step per
//                     communication step)
// and one Integer, `ensemble_member` (value reference 0): 0 the estimate, k the k-th draw.
#pragma once

#include <string>
#include <vector>

#include "engine/export/model_json.h"

namespace vesselid {

struct FmuLayout {
  explicit FmuLayout(const IdentifiedModel& model) {
    const int nu = static_cast<int>(model.inputs.size());
    const int ny = static_cast<int>(model.outputs.size());
    for (size_t i = 0; i < model.states.size(); ++i) {
      bool output = false;
      for (const ModelVariable& o : model.outputs) output |= o.name == model.states[i].name;
      if (!output) state_outputs.push_back(static_cast<int>(i));
    }
    first_input = 0;
    first_output = nu;
    first_state_output = first_output + ny;
    first_parameter = first_state_output + static_cast<int>(state_outputs.size());
    first_initial_state = first_parameter + static_cast<int>(model.parameters.size());
    max_step = first_initial_state + static_cast<int>(model.states.size());
    reals = max_step + 1;
  }
  int first_input, first_output, first_state_output, first_parameter, first_initial_state;
  int max_step, reals;
  std::vector<int> state_outputs;  // state index of each state output
  static constexpr int kEnsembleMember = 0;  // the Integer's value reference
};

}  // namespace vesselid
