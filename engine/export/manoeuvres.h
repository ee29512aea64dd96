// The standard manoeuvres a naval architect checks, predicted by an identified model with 95 %
// intervals (`vesselid predict`): the 10/10 and 20/20 zigzags of IMO MSC.137(76) /
// MSC/Circ.1053 (first and second overshoot angles) and the initial turning ability (the
// distance run, in ship lengths, until the heading has changed 10 deg with 10 deg of rudder),
// for every model with a rudder input `delta` and a heading output `psi`; and the pull-out
// test's residual yaw rate (MSC/Circ.1053: after a steady turn on 20 deg of rudder, the rudder
// to midships; a rate that stays means a course-unstable ship, the spiral test's loop).
//
// Each zigzag is simulated in closed loop from a straight course (every state zero): the rudder
// goes to +delta_z at t = 0 at the steering gear's rate and is reversed each time the heading
// change reaches +-psi_z; the figures are measured on the heading as data/zigzag_figures.h
// measures a trial's. Intervals: the 2.5 and 97.5 percentiles of the figure over the model's
// ensemble members (draws from the covariance, output/identified_model.h), and the delta method
// (value +- 1.96 sqrt(J C J^T), J by central differences), with whether the two agree (their
// half-widths within a factor 1.5). Where the ship's length L and speed U are known, each
// figure is held against its IMO criterion for L/U. Where the model's stage identified process
// noise with the ship (a filter-error stage's gusts, process_noise.h), a third interval flies
// every member again in its own realisation of it: the spread a trial in that sea would show.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/data/zigzag_figures.h"
#include "engine/export/model_json.h"
#include "engine/model/model_handle.h"
#include "engine/output/process_noise.h"

namespace vesselid {

struct ManoeuvreConditions {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  double length = kUnknown;  // m, L
  double speed = kUnknown;   // m/s, the approach speed U (the model's input U where it has one)
  double rudder_rate = kImoRudderRate;  // rad/s, the steering gear's (data/zigzag_figures.h)
  double step = 0.01;        // s, RK4 step of the closed-loop simulation (and the checks' timing)
  double duration = 3600.0;  // s, the longest a zigzag is simulated
  // s: the pull-out test's steady turn on 20 deg of rudder, and the time it is then watched
  // with the rudder at midships.
  double pull_out_turn = 900.0, pull_out_settle = 900.0;
  double pull_out_step = 0.1;  // s, its RK4 step (no check to time)
};

struct ManoeuvreFigure {
  std::string name;  // "zigzag_10_10.first_overshoot", "initial_turning"
  std::string unit;  // "deg", "ship lengths", "s"
  double value = ManoeuvreConditions::kUnknown;  // the estimate's
  double ensemble_low = ManoeuvreConditions::kUnknown,
         ensemble_high = ManoeuvreConditions::kUnknown;
  int members = 0;  // ensemble members whose figure exists
  double delta_low = ManoeuvreConditions::kUnknown, delta_high = ManoeuvreConditions::kUnknown;
  // Where the run identified process noise (ManoeuvrePredictions::process_noise): the same
  // members flown each in its own realisation of it, the 2.5 and 97.5 percentiles: where a
  // trial in the sea the model was identified in would fall, not only the model's uncertainty.
  double disturbance_low = ManoeuvreConditions::kUnknown,
         disturbance_high = ManoeuvreConditions::kUnknown;
  int disturbance_members = 0;  // members whose figure exists in the sea
  bool agree = false;  // delta-method and ensemble half-widths within a factor 1.5
  // The IMO criterion (NaN: none, or L and U unknown), and whether the value and the whole
  // ensemble interval meet it.
  double limit = ManoeuvreConditions::kUnknown;
  std::string criterion;  // its text, e.g. "<= 5 + 0.5 L/U deg for 10 <= L/U < 30 s"
  bool meets = false, interval_meets = false;
};

struct ManoeuvrePredictions {
  std::vector<ManoeuvreFigure> figures;
  double length = ManoeuvreConditions::kUnknown, speed = ManoeuvreConditions::kUnknown;
  std::vector<std::string> notes;  // what could not be predicted, and why
  std::vector<ProcessNoise> process_noise;  // flown in the disturbance interval; empty: none
};

// False with a message when the model has no rudder input `delta` or heading output `psi`, or
// needs an input nothing gives (the speed U without `speed`).
bool PredictManoeuvres(const IdentifiedModel& model, const ModelHandle& handle,
                       const ManoeuvreConditions& conditions, ManoeuvrePredictions* predictions,
                       std::string* error);

// The figures as a table (report text) and as JSON.
std::string ManoeuvresText(const ManoeuvrePredictions& predictions);
nlohmann::json ManoeuvresToJson(const ManoeuvrePredictions& predictions);

}  // namespace vesselid
