// A recorded zigzag re-flown in closed loop, as the test was flown: from the record's start
// state, the logged rudder until the first execute t_0, then the rudder commanded to the
// record's plateaus c +- delta_z (c the rudder's neutral as logged) and reversed each time the
// *simulated* heading change from psi_0 reaches the record's check, moving at the steering
// gear's rate.
// Other inputs (a propeller's revolutions, the speed U) stay as logged. The figures
// (data/zigzag_figures.h: first and second overshoot, time to the first check, period) are
// then measured on the simulated heading, to be held against the record's own.
//
// Why: an open-loop fit on the logged rudder judges a model by the rudder the *ship* chose.
// A model whose heading runs a little ahead of the record gets the rudder reversal late, and
// the open-loop heading drifts for the rest of the run, which says little of what a user
// needs (the overshoots). Re-flown, the model reverses the rudder where it itself reaches the
// check, as a trial's helmsman would, and its overshoots compare directly with the measured
// ones (issue 73; the smallest zigzags, 5/1 and 10/1, vary the heading by about 1 deg).
//
// The integration walks the experiment's own RK4 grid (node_step, node_substeps), its inputs
// from the experiment's input cache, the rudder column replaced from t_0 on.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/data/zigzag_figures.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"

namespace vesselid {

// The rudder of a zigzag as commanded: its neutral c and amplitude delta_z (rad) from the
// plateaus of the logged rudder (the medians of the samples in the outer halves of its range),
// the sign of the first command after t_0, and the check: the heading change from psi_0 at
// which the rudder left each plateau (the median over the reversals). The check is not the
// psi_z DetectZigzag reports, which is read where the rudder has crossed half its travel: a
// gear at 4 deg/s then puts it 1.8 deg beyond the 20 deg the helmsman reversed at.
struct ZigzagCommands {
  double neutral = 0.0;
  double amplitude = 0.0;
  double first_sign = 1.0;  // +1: the first command is c + delta_z
  double check = 0.0;       // rad, the heading change that reverses the rudder
  double rate = NAN;        // rad/s, the gear's: the median slope of the reversals' ramps
};

// The commands of the logged rudder `delta` and heading `psi` at times `t` for `test`
// (DetectZigzag's); false with `why` when the rudder has no plateau either side of its
// neutral or never leaves one.
bool FindZigzagCommands(const std::vector<double>& t, const std::vector<double>& delta,
                        const std::vector<double>& psi, const ZigzagTest& test,
                        ZigzagCommands* commands, std::string* why);

struct ZigzagReflight {
  std::vector<double> t, psi, delta;  // every RK4 step's end (t[0]: the record's start)
  int reversals = 0;                  // of the closed loop, after t_0
  ZigzagFigures figures;              // measured on psi for the re-flown test
};

// Flies `experiment` (whose inputs include `delta`, outputs `psi`) with parameters p from x0
// (the model's state at the record's start), closed loop from test.first_execute on, the
// rudder moving at most `rudder_rate` (rad/s). False with `why` where the model has no
// rudder input or heading output, or the simulation leaves finite numbers; figures the record
// is too short for stay NaN.
bool ReflyZigzag(const ModelHandle& model, const Experiment& experiment, const double* p,
                 const double* x0, const ZigzagTest& test, const ZigzagCommands& commands,
                 double rudder_rate, ZigzagReflight* reflight, std::string* why);

}  // namespace vesselid
