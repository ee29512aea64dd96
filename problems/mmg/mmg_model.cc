#include "problems/mmg/mmg_model.h"

#include <cmath>

namespace vesselid::mmg {

bool Ship::IsValid(std::string* error) const {
  const std::pair<const char*, double> positive[] = {{"length", length},
                                                     {"draft", draft},
                                                     {"displacement", displacement},
                                                     {"radius_of_gyration", radius_of_gyration},
                                                     {"propeller_diameter", propeller_diameter},
                                                     {"rudder_area", rudder_area},
                                                     {"rudder_height", rudder_height},
                                                     {"water_density", water_density}};
  for (const auto& [name, value] : positive) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      *error = std::string(name) + " must be a number > 0";
      return false;
    }
  }
  if (!std::isfinite(centre_of_gravity) || !std::isfinite(rudder_position)) {
    *error = "centre_of_gravity and rudder_position must be finite";
    return false;
  }
  return true;
}

ModelInfo Model::Info() const {
  ModelInfo info;
  info.name = "mmg";
  info.states = {"x", "y", "psi", "u", "v", "r"};
  info.inputs = {"delta", "n"};
  info.outputs = {"x", "y", "psi", "u", "v", "r", "U"};
  info.angle_outputs = {false, false, true, false, false, false, false};
  info.output_units = {"m", "m", "rad", "m/s", "m/s", "rad/s", "m/s"};
  info.state_units = {"m", "m", "rad", "m/s", "m/s", "rad/s"};
  info.input_units = {"rad", "1/s"};
  info.positive_inputs = {false, true};
  // Yasukawa & Yoshimura 2015, Tables 2-4 (KVLCC2); x'_P from their Table 3.
  const std::pair<const char*, double> coefficients[kNumParameters] = {{"R0", 0.022},
                                                                       {"X_vv", -0.040},
                                                                       {"X_vr", 0.002},
                                                                       {"X_rr", 0.011},
                                                                       {"X_vvvv", 0.771},
                                                                       {"Y_v", -0.315},
                                                                       {"Y_r", 0.083},
                                                                       {"Y_vvv", -1.607},
                                                                       {"Y_vvr", 0.379},
                                                                       {"Y_vrr", -0.391},
                                                                       {"Y_rrr", 0.008},
                                                                       {"N_v", -0.137},
                                                                       {"N_r", -0.049},
                                                                       {"N_vvv", -0.030},
                                                                       {"N_vvr", -0.294},
                                                                       {"N_vrr", 0.055},
                                                                       {"N_rrr", -0.013},
                                                                       {"m_x", 0.022},
                                                                       {"m_y", 0.223},
                                                                       {"J_z", 0.011},
                                                                       {"t_P", 0.220},
                                                                       {"w_P0", 0.40},
                                                                       {"k_0", 0.2931},
                                                                       {"k_1", -0.2753},
                                                                       {"k_2", -0.1385},
                                                                       {"x_P", -0.48},
                                                                       {"C_1", 2.0},
                                                                       {"C_2_plus", 1.6},
                                                                       {"C_2_minus", 1.1},
                                                                       {"t_R", 0.387},
                                                                       {"a_H", 0.312},
                                                                       {"x_H", -0.464},
                                                                       {"epsilon", 1.09},
                                                                       {"kappa", 0.50},
                                                                       {"l_R", -0.710},
                                                                       {"gamma_R_plus", 0.640},
                                                                       {"gamma_R_minus", 0.395},
                                                                       {"f_alpha", 2.747},
                                                                       {"delta_0", 0.0}};
  for (const auto& [name, value] : coefficients) {
    info.parameters.push_back(name);
    info.parameter_defaults.push_back(value);
  }
  info.parameter_units.assign(kNumParameters, "");
  info.parameter_units[kDelta0] = "rad";
  info.parameter_channels = {{"delta_0", "delta"}};
  info.positive_parameters.assign(kNumParameters, false);
  for (int i : {kMx, kMy, kJz, kEpsilon, kFalpha, kGammaPlus, kGammaMinus}) {
    info.positive_parameters[i] = true;
  }
  info.compensation_hints = {
      {"Y_vvr", "hold one of the cubic cross terms (Y_vvr, Y_vrr) at a captive-test value"},
      {"N_vvr", "hold one of the cubic cross terms (N_vvr, N_vrr) at a captive-test value"},
      {"gamma_R_plus",
       "the flow-straightening and lateral-force terms trade off: hold "
       "gamma_R or the linear sway derivatives at captive-test values"},
      {"f_alpha",
       "the rudder's lift slope scales with a_H and x_H: hold f_alpha at its "
       "open-water value"}};
  return info;
}

void Model::GuessState(const double* y, const double* ydot, double* x) const {
  const double psi = std::isfinite(y[2]) ? y[2] : x[2];
  if (std::isnan(y[3]) || std::isnan(y[4])) {
    if (std::isfinite(ydot[0]) && std::isfinite(ydot[1])) {
      const double c = std::cos(psi), s = std::sin(psi);
      if (std::isnan(y[3])) x[3] = ydot[0] * c + ydot[1] * s;
      if (std::isnan(y[4])) x[4] = -ydot[0] * s + ydot[1] * c;
    } else if (std::isnan(y[3]) && std::isfinite(y[6])) {
      x[3] = y[6];
      if (std::isnan(y[4])) x[4] = 0.0;
    }
  }
  if (std::isnan(y[5]) && std::isfinite(ydot[2])) x[5] = ydot[2];
}

}  // namespace vesselid::mmg
