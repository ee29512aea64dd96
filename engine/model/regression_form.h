// The equation-error form of a model that is linear in its parameters (or in products of
// them) once its states are known from the data, for the least-squares stage:
//
//   x'[states[i]](t_k) = phi_i(k) . theta_i(p)       for each regressed state i
//
// theta_i are the regression coefficients (e.g. b_u k_f), each a known function of the model
// parameters; phi_i(k) the regressors, computed from the record's states and inputs. The
// `profiled` parameters enter the regressors themselves (a propeller time constant that
// filters the inputs, a dead zone): the stage searches them and regresses the rest.
//
// A model opts in with four members (see ModelHandle):
//   RegressionForm Regression() const;
//   void Regressors(const double* p, RegressionRecord* record,
//                   std::vector<Eigen::MatrixXd>* phi) const;  // may fill internal states
//   void Coefficients(const double* p, double* theta) const;   // all equations, in order
//   int Region(const double* u) const;                          // operating region of inputs
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {

struct RegressionForm {
  std::vector<int> states;                              // regressed states
  std::vector<std::vector<std::string>> coefficients;   // names of theta_i, per equation
  std::vector<int> profiled;                            // parameters inside the regressors
  std::vector<std::string> regions;                     // names of Region() values

  int num_coefficients() const {
    int n = 0;
    for (const auto& c : coefficients) n += static_cast<int>(c.size());
    return n;
  }
};

// One record (experiment or segment) on a uniform regression grid.
struct RegressionRecord {
  std::string name;    // experiment name (a segment's own name)
  std::string record;  // the configured experiment it comes from
  int grid_output = 0;  // model output whose sample times are t
  double dt = 0.0;
  std::vector<double> t;
  Eigen::MatrixXd x;     // grid x states: from the outputs and their rates (model's guess)
  Eigen::MatrixXd xdot;  // grid x states: derivatives of x
  Eigen::MatrixXd u;     // grid x inputs: last sample at or before t (causal)
  std::vector<int> region;  // per grid sample; -1 when the model has no regions
  std::vector<bool> use;    // per grid sample: selected (partition studies)

  int size() const { return static_cast<int>(t.size()); }
};

}  // namespace vesselid
