// The model concept. A model is an immutable plain struct:
//
//   struct MyModel {
//     static constexpr int kNumStates, kNumInputs, kNumOutputs;
//     ModelInfo Info() const;                        // names, in the order of the arrays below
//     template <class T, class U>                     // T = double or ceres::Jet; U = double,
//     bool operator()(const T* x, const U* u, const T* p, T* xdot) const;  // or T where the
//     template <class T, class U>                     // inputs are estimated (input_noise.h)
//     void Output(const T* x, const U* u, const T* p, T* y) const;
//   };
//
// Optional members, found by ModelAdapter when present:
//
//     std::vector<std::string> Admissibility(const double* p,           // physical conditions
//                                            const double* state_limits) const;  // (see
//                                            // ModelHandle::Admissibility)
//     void GuessState(const double* y, const double* ydot, double* x) const;  // see ModelHandle
//
// xdot = f(x, u, p) is the right-hand side; it returns false for an inadmissible or
// non-finite state so that a diverging simulation fails the evaluation instead of
// poisoning the solver. Known constants are double members, cast with T(...).
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/angle.h"

namespace vesselid {

struct ModelInfo {
  std::string name;
  std::vector<std::string> states;
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  std::vector<std::string> parameters;
  std::vector<double> parameter_defaults;  // typical values, one per parameter
  // Outputs that are angles: their measurements are unwrapped when read (continuous across
  // +-pi) and compared with the simulated angle as they are, unless an experiment lists them
  // in `wrap` (ExperimentSpec::wrapped_outputs).
  std::vector<bool> angle_outputs;
  // Parameter pairs the model is symmetric in (e.g. Nomoto T1, T2); reported first >= second.
  std::vector<std::pair<int, int>> exchangeable;
  // Inputs an experiment may leave unmapped; the model then sees NaN and decides what that
  // means (e.g. motors off, still air). Empty: every input is required.
  std::vector<bool> optional_inputs;
  // Units of the outputs, states and inputs as labels show them ("m", "m/s", "rad", "rad/s",
  // "N"; empty: not stated). An angle read in degrees is shown in degrees ("rad" -> "deg").
  std::vector<std::string> output_units = {}, state_units = {}, input_units = {};
  // Units of the parameters ("s", "1/s", "rad"; empty: not stated), and for a parameter that
  // is an angle of a channel (a rudder bias is an angle of the rudder), that channel (an
  // input or output name): the parameter is shown in degrees where that channel's column is
  // read in degrees (display_units.h).
  std::vector<std::string> parameter_units = {};
  std::map<std::string, std::string> parameter_channels = {};

  // output_units, else "rad" for an angle output, else "".
  std::string OutputUnit(int index) const;
  // state_units, else the unit of the same-named output.
  std::string StateUnit(int index) const;
  std::string InputUnit(int index) const;
  std::string ParameterUnit(int index) const;
  // The horizontal position outputs (north, east): the first two outputs in metres; -1 when
  // the model has none (no x-y track in the report).
  std::pair<int, int> TrackOutputs() const;
  // Inputs whose every sample must be > 0 (a speed a model divides by); a record with one that
  // is not is refused, naming the column and time.
  std::vector<bool> positive_inputs = {};
  // Per parameter name, what to change in the model's structure when its estimate compensates
  // another (|correlation| > 0.999) or ends at a bound: appended to those findings.
  std::map<std::string, std::string> compensation_hints = {};
  // Parameters that are positive by their nature (time constants, masses): a global start
  // searches them in log coordinates also when their lower bound is 0 (search_box.h).
  std::vector<bool> positive_parameters = {};

  bool InputOptional(int index) const {
    return index < static_cast<int>(optional_inputs.size()) && optional_inputs[index];
  }
  bool InputPositive(int index) const {
    return index < static_cast<int>(positive_inputs.size()) && positive_inputs[index];
  }
  bool ParameterPositive(int index) const {
    return index < static_cast<int>(positive_parameters.size()) && positive_parameters[index];
  }
  int ParameterIndex(const std::string& name) const;
  int StateIndex(const std::string& name) const;
  int InputIndex(const std::string& name) const;
  int OutputIndex(const std::string& name) const;
};

// Joins names as "a, b, c" for messages.
std::string JoinNames(const std::vector<std::string>& names);

}  // namespace vesselid
