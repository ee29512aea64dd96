// Structure the filter's innovations follow. Under a correct ship and disturbance model the
// innovations are a martingale difference sequence: uncorrelated with every function of what
// was known before their sample, whatever the noise (gusts, waves, a drifting sensor). A ship
// model that lacks a term (a rudder's dead band or backlash, a cubic damping) leaves innovations
// that follow nonlinear functions of the predicted motion and of the inputs, even where process
// noise has whitened them in time (the Lagrange-multiplier test of a regression on those
// functions: N R^2 ~ chi^2(m) under a correct model).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct InnovationStructure {
  std::string experiment, output;
  int samples = 0;
  int features = 0;  // m
  double statistic = std::numeric_limits<double>::quiet_NaN();  // N R^2
  double p_value = std::numeric_limits<double>::quiet_NaN();    // P(chi^2(m) > N R^2)
};

// Per experiment and compared output of a filter-error problem at its current values: the
// normalised innovations regressed on s, s|s| and s^3 of each s in {the output's predicted
// rate of change over the two samples before, each input at the node before the sample} (each
// s scaled by its SD). Empty for output error.
std::vector<InnovationStructure> TestInnovationStructure(const OutputErrorProblem& problem);

// The family-wise level of the test over a stage's experiments and outputs (Bonferroni): on
// the independent corpus's sensor, wave, gust and drift classes N R^2 reached 11.1 of 6
// functions (p 0.09); its dead band, rate limit and cubic damping classes 9.6-119.
inline constexpr double kInnovationStructureLevel = 1e-3;

// A note per test, and the disturbance_absorbs_structure finding naming the experiments
// whose p lies below kInnovationStructureLevel / (number of tests).
void AddInnovationStructureFindings(const std::string& stage,
                                    const std::vector<InnovationStructure>& tests,
                                    std::vector<std::string>* notes,
                                    std::vector<Finding>* findings);

// P(chi^2(m) > x) by the Wilson-Hilferty cube-root normal approximation (within a few per cent
// of the tail probability for m >= 3 down to 1e-6).
double ChiSquareTail(double x, int m);

}  // namespace vesselid
