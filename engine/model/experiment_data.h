// How a record's raw columns become an experiment's data, between the CSV reader and
// BuildExperiment (LoadExperimentData): epoch times made relative (time_base.h), GNSS fixes
// mapped to north/east metres (gnss_position.h), glitches removed from the measured outputs
// (glitch_screen.h), degree columns converted to radians, and the record brought to a
// uniform grid (resample.h). Every change that removes or invents samples leaves one note
// per experiment in Trajectory::notes.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/data/gnss_position.h"

namespace vesselid {

struct ExperimentDataSpec {
  // time: {unit: s | ms | us | min}: seconds per unit of the time column, applied as read.
  double time_scale = 1.0;
  // position: {lat, lon, origin}: adds channels `north` and `east`.
  bool position = false;
  GnssPositionOptions gnss;
  // screen: {max_speed, max_rate: {<output>: rate}, stale, zero_fix}
  bool screen = false;
  double max_speed = 0.0;                  // m/s of the position pair, 0: not checked
  std::map<std::string, double> max_rate;  // model output -> its column's unit per second
  int stale = 0;                           // repeats in a row that are stale, 0: not checked
  bool zero_fix = true;
  bool zero_fix_given = false;  // the key was in the config (it needs positions to act on)
  std::string screen_key;  // config key, for messages
  // resample: {rate, max_gap}
  double resample_rate = 0.0;  // Hz, 0: the record's own times
  double resample_max_gap = 3.0;
  // The model's outputs that are angles (compared modulo a turn by the screen, unwrapped
  // before interpolation); set by the config.
  std::vector<std::string> angle_outputs;
};

}  // namespace vesselid
