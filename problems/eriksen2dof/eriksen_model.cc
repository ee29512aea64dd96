#include "problems/eriksen2dof/eriksen_model.h"

namespace vesselid::eriksen2dof {

ModelInfo Model::Info() const {
  ModelInfo info;
  info.name = "eriksen2dof";
  info.states = {"N", "E", "chi", "U", "r"};
  info.inputs = {"tau_m", "tau_delta"};
  info.outputs = info.states;
  info.angle_outputs = {false, false, true, false, false};
  info.output_units = {"m", "m", "rad", "m/s", "rad/s"};
  const std::vector<std::string> monomials = MonomialNames(kDegree, "U", "r");
  // Defaults: a plausible planing craft in the scaled states (sigma_U ~ U, sigma_r ~ r,
  // inertias ~ 0.2), so that a run without a regression stage still simulates.
  auto add = [&](const std::string& term, double constant, int linear) {
    for (int k = 0; k < kBasis; ++k) {
      info.parameters.push_back(term + "." + monomials[k]);
      info.parameter_defaults.push_back(k == 0 ? constant : k == linear ? 1.0 : 0.0);
    }
  };
  add("sigma_U", 0.0, 1);
  add("sigma_r", 0.0, 2);
  add("m_U", 0.2, -1);
  info.parameters.push_back("m_U.tanh");
  info.parameter_defaults.push_back(0.0);
  add("m_r", 0.2, -1);
  info.parameters.push_back("m_r.tanh");
  info.parameter_defaults.push_back(0.0);
  info.parameters.insert(info.parameters.end(), {"m_U.a", "m_U.b", "m_r.a", "m_r.b"});
  info.parameter_defaults.insert(info.parameter_defaults.end(), {1.0, 5.0, 1.0, 5.0});
  return info;
}

DampingInertiaForm Model::DampingInertia() const {
  DampingInertiaForm form;
  form.degree = kDegree;
  form.states = {3, 4};
  form.inputs = {0, 1};
  form.scale = {speed_scale, yaw_rate_scale};
  form.damping.resize(2);
  form.inertia.resize(2);
  for (int k = 0; k < kBasis; ++k) {
    form.damping[0].push_back(kSigmaU + k);
    form.damping[1].push_back(kSigmaR + k);
  }
  for (int k = 0; k <= kBasis; ++k) {
    form.inertia[0].push_back(kInertiaU + k);
    form.inertia[1].push_back(kInertiaR + k);
  }
  form.asymptote_a = {kAsymptote, kAsymptote + 2};
  form.asymptote_b = {kAsymptote + 1, kAsymptote + 3};
  form.asymptote_state = 0;
  form.turning_state = 1;
  form.term_names = {"sigma_U", "sigma_r", "m_U", "m_r"};
  return form;
}

}  // namespace vesselid::eriksen2dof
