// The commands a plan is made of. A design is a point z in the unit box [0, 1]^m; each
// designed input takes its share of z (design_options.h):
//   steps:     levels lower + z_j (upper - lower), one per `hold` s;
//   multisine: amplitudes z (upper - lower) / 2 and phases 2 pi z, one pair per period;
//   zigzag:    the rudder a = z_0 max(|lower|, |upper|) and the switch heading
//              psi_z = headings.first + z_1 (headings.second - headings.first).
// The standard alternatives of the same duration are commands too: the 10/10 and 20/20
// zigzags (IMO MSC.137(76)), a spiral's held rudder steps (+25, +15, +5, -5, -15, -25 deg),
// a Schroeder-phased multi-sine over every designed input and a random binary sequence
// (MATLAB idinput's PRBS) over them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/design/design_options.h"
#include "engine/design/planned_record.h"
#include "engine/model/model.h"

namespace vesselid {

// Where each designed input's variables lie in z, and the model's rudder and heading.
struct DesignLayout {
  std::vector<int> input;         // per DesignOptions::inputs: the model input index
  std::vector<int> first, count;  // per DesignOptions::inputs: its variables in z
  int variables = 0;
  int rudder = -1;   // the model input `delta` (alternatives' zigzags and spiral), or -1
  int heading = -1;  // the model output `psi`, or -1
  double duration = 0.0;
  int num_inputs = 0;  // the model's
};

// False, naming the input and the shortest hold, when a steps input's levels over `duration`
// (duration / hold) are more than one search plans (each level is a variable of NLopt's and
// the multistart's search, each evaluation a simulation of the plan).
bool StepsFitTheSearch(const DesignOptions& options, double duration, std::string* error);

// Checks the inputs against the model (every input planned once, a zigzag needs `delta` and
// `psi`) and lays out z; false with a message naming the key.
bool MakeDesignLayout(const ModelInfo& info, const DesignOptions& options, double duration,
                      DesignLayout* layout, std::string* error);

// The actuators of every model input: the designed inputs' limits, the others held at their
// `value` (fixed) or at 0.
Actuators MakeActuators(const ModelInfo& info, const DesignOptions& options,
                        const DesignLayout& layout);

// A command and whether it has finished (a zigzag after its reversals); `reversals` counts a
// zigzag's rudder reversals.
struct Manoeuvre {
  InputCommand command;
  std::shared_ptr<int> reversals = std::make_shared<int>(0);
  int stop_after = 0;  // > 0: the record ends at this many reversals
  std::function<bool()> Stop() const {
    if (stop_after <= 0) return {};
    auto count = reversals;
    const int limit = stop_after;
    return [count, limit] { return *count >= limit; };
  }
};

// The design that holds every input at its value (steps at the value, no sine, no rudder):
// a start that keeps any box around the start.
std::vector<double> QuietDesign(const DesignOptions& options, const DesignLayout& layout);

// The command of design z.
Manoeuvre CommandOf(const DesignOptions& options, const DesignLayout& layout,
                    const std::vector<double>& z);

// A delta_z / psi_z zigzag on the rudder (others at their values); psi_0 is read at t = 0.
Manoeuvre Zigzag(const DesignOptions& options, const DesignLayout& layout, double rudder,
                 double heading);

// The standard alternatives the model's inputs allow, by name (zigzag_10_10, zigzag_20_20,
// spiral, multisine, prbs), each limited like the plan.
std::vector<std::pair<std::string, Manoeuvre>> Alternatives(const DesignOptions& options,
                                                            const DesignLayout& layout);

}  // namespace vesselid
