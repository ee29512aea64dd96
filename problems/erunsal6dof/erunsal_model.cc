#include "problems/erunsal6dof/erunsal_model.h"

#include "Eigen/Dense"

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
  return info;
}

std::vector<std::string> Model::Admissibility(const double* p) const {
  std::vector<std::string> problems;
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  const double m = constants.m;
  M.diagonal() << m - p[kXudot], m - p[kYvdot], m - p[kZwdot], p[kIx] - p[kKpdot],
      p[kIy] - p[kMqdot], p[kIz] - p[kNrdot];
  M(3, 5) = M(5, 3) = -p[kIxz];
  M(1, 5) = M(5, 1) = -p[kYrdot];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> mass(M);
  if (mass.eigenvalues().minCoeff() <= 0.0) {
    problems.push_back("M is not positive definite (smallest eigenvalue " +
                       std::to_string(mass.eigenvalues().minCoeff()) + ")");
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
