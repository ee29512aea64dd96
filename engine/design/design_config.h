// The `design:` section of a config (`vesselid design`):
//
//   design:
//     duration: zigzag_20_20          # s, or the time the model takes for a 20/20 zigzag
//     sample_time: 0.1                # s, the planned log's sample interval (required)
//     criterion: D                    # | A | E | {parameter: T3}
//     inputs:                         # every model input: a family and its limits
//       delta: {family: steps, lower: -35, upper: 35, rate: 15, hold: 2, degrees: true}
//       U: {family: fixed, value: 7.7}
//     box: {n: [-100, 100], e: [-50, 300]}   # the track relative to the start, outputs' units
//     noise: {psi: 0.00175}           # per output, model units (default: the fit's RMS)
//     noise_deg: {psi: 0.1}           # the same in degrees
//     initial_state: {u: 1.5}         # model units (default 0)
//     settle: 60                      # s at the inputs' values first (a craft under way)
//     free_initial_states: [psi]      # estimated from the planned log (default: the run's)
//     search: {starts: 24, refined: 3, max_evaluations: 1500, seed: 1, threads: 0}
//     robust: {members: 20}           # the criterion over the run's ensemble
//
// An input's keys: family (steps | multisine | zigzag | fixed), lower, upper, rate (per s,
// 0: none), value (when not excited; default 0, or the middle of a range without 0), hold
// (steps, s), periods (multisine, s), headings (zigzag, [lowest, highest] in degrees, default
// [5, 30]), degrees.
#pragma once

#include <string>

#include "engine/design/design_options.h"

namespace vesselid {

// False with a message naming the file, line and key. With `text`, the config is that text
// (YAML or JSON) and `path` the name messages give it.
bool LoadDesign(const std::string& path, DesignOptions* options, std::string* error,
                const std::string& text = "");

}  // namespace vesselid
