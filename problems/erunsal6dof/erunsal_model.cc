#include "problems/erunsal6dof/erunsal_model.h"

#include <cmath>
#include <cstdio>

#include "Eigen/Dense"
#include "Eigen/Geometry"

namespace vesselid::erunsal6dof {

namespace {
const char* const kDofNames[] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};
}  // namespace

const char* DofToString(int dof) { return kDofNames[dof]; }

bool StringToDof(const std::string& text, int* dof) {
  for (int i = 0; i < 6; ++i) {
    if (text == kDofNames[i]) {
      *dof = i;
      return true;
    }
  }
  return false;
}

std::vector<std::string> ParameterNames() {
  return {"Ix",    "Iy",    "Iz",    "Ixz",   "Xudot", "Yvdot", "Yrdot", "Nrdot",
          "Zwdot", "Kpdot", "Mqdot", "Xu",    "Yv",    "Zw",    "Kp",    "Mq",
          "Nr",    "Yr",    "Nv",    "Xuu",   "Yvv",   "Zww",   "Kpp",   "Mqq",
          "Nrr",   "C_DA",  "L_TS",  "L_TO",  "R_TS",  "R_TO"};
}

std::vector<double> ReferenceParameters() {
  return {0.15,    0.75,    0.80,    0.02,    -1.0946, -1.0536, -1.4353, -0.0474,
          -5.5,    -0.01,   -0.30,   -5.6128, -3.5059, -20.0,   -0.08,   -1.5,
          -0.1039, -0.0001, -1.0005, -2.3136, -3.9310, -30.0,   -0.05,   -1.0,
          -0.2605, 0.6487,  10.2,    0.10,    9.8,     -0.10};
}

void Model::GuessState(const double* y, const double* ydot, double* x) const {
  auto rate = [&](int i) { return active[i] && std::isfinite(ydot[i]) ? ydot[i] : 0.0; };
  auto known = [&](int first) {
    return std::isfinite(ydot[first]) || std::isfinite(ydot[first + 1]) ||
           std::isfinite(ydot[first + 2]);
  };
  const double phi = x[3], theta = x[4], psi = x[5];
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  double nu[6];
  const Eigen::Vector3d linear = R.transpose() * Eigen::Vector3d(rate(0), rate(1), rate(2));
  const double phi_dot = rate(3), theta_dot = rate(4), psi_dot = rate(5);
  const double angular[3] = {phi_dot - std::sin(theta) * psi_dot,
                             std::cos(phi) * theta_dot + std::sin(phi) * std::cos(theta) * psi_dot,
                             -std::sin(phi) * theta_dot + std::cos(phi) * std::cos(theta) * psi_dot};
  for (int i = 0; i < 3; ++i) {
    nu[i] = linear[i];
    nu[3 + i] = angular[i];
  }
  for (int i = 0; i < 6; ++i) {
    const bool derivable = known(i < 3 ? 0 : 3);
    if (active[i] && derivable && std::isnan(y[6 + i])) x[6 + i] = nu[i];
  }
}

ModelInfo Model::Info() const {
  ModelInfo info;
  info.name = "erunsal6dof";
  info.states = {"x", "y", "z", "phi", "theta", "psi", "u", "v", "w", "p", "q", "r"};
  info.inputs = {"c_L", "c_R", "wind_speed", "wind_direction"};
  info.optional_inputs = {true, true, true, true};
  info.outputs = info.states;
  info.outputs.push_back("F_L");
  info.outputs.push_back("F_R");
  info.parameters = ParameterNames();
  info.parameter_defaults = ReferenceParameters();
  info.angle_outputs.assign(info.outputs.size(), false);
  info.angle_outputs[3] = info.angle_outputs[4] = info.angle_outputs[5] = true;
  info.output_units = {"m",   "m",   "m",     "rad",   "rad",   "rad", "m/s",
                       "m/s", "m/s", "rad/s", "rad/s", "rad/s", "N",   "N"};
  info.input_units = {"", "", "m/s", "rad"};
  return info;
}

std::vector<std::string> Model::Admissibility(const double* p, const double*) const {
  std::vector<std::string> problems;
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  const double m = constants.m;
  M.diagonal() << m - p[kXudot], m - p[kYvdot], m - p[kZwdot], p[kIx] - p[kKpdot],
      p[kIy] - p[kMqdot], p[kIz] - p[kNrdot];
  M(3, 5) = M(5, 3) = -p[kIxz];
  M(1, 5) = M(5, 1) = -p[kYrdot];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> mass(M);
  if (mass.eigenvalues().minCoeff() <= 0.0) {
    std::string text = "M is not positive definite (smallest eigenvalue " +
                       std::to_string(mass.eigenvalues().minCoeff()) + ")";
    // The diagonal terms that are not positive by themselves: rigid body minus added mass.
    const char* rigid[6] = {"m", "m", "m", "Ix", "Iy", "Iz"};
    const char* added[6] = {"Xudot", "Yvdot", "Zwdot", "Kpdot", "Mqdot", "Nrdot"};
    const double body[6] = {m, m, m, p[kIx], p[kIy], p[kIz]};
    for (int i = 0; i < 6; ++i) {
      if (M(i, i) > 0.0) continue;
      char term[160];
      std::snprintf(term, sizeof(term), ": %s - %s = %g - %g <= 0", rigid[i], added[i], body[i],
                    body[i] - M(i, i));
      text += term;
    }
    problems.push_back(text);
  }
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.diagonal() << -p[kXu], -p[kYv], -p[kZw], -p[kKp], -p[kMq], -p[kNr];
  D(1, 5) = -p[kYr];
  D(5, 1) = -p[kNv];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> damping(0.5 * (D + D.transpose()));
  if (damping.eigenvalues().minCoeff() < 0.0) {
    problems.push_back("the symmetric part of the linear damping is not positive semi-definite "
                       "(smallest eigenvalue " +
                       std::to_string(damping.eigenvalues().minCoeff()) + ")");
  }
  return problems;
}

}  // namespace vesselid::erunsal6dof
