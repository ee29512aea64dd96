// The score test of terms the ship model lacks, under the filter-error method with process
// noise (omitted_terms.h). Process noise can stand in for missing structure: a dead band or a
// missing damping term becomes "gusts" and the innovations come out white. What it cannot do
// is make the likelihood indifferent to the missing term: its score, taken through the filter
// (the innovations' sensitivity to the term, not the term itself), stays away from zero.
//
// Candidates, on every state the process noise acts on: a constant, and z, z|z|, z^3 and a smoothed sign
// z / sqrt(z^2 + 0.05^2) of every
// velocity state and every input (z scaled by its size in the records). The stage's free
// unknowns are the nuisance: with g and I the likelihood's score and information over
// (free unknowns b, candidates a), the efficient score and its information
//
//   g_a* = g_a - I_ab I_bb^+ g_b,    C = I_aa - I_ab I_bb^+ I_ba,    LM = g_a*' C^+ g_a*
//
// and LM ~ chi^2(rank C) under a correct ship and disturbance model (Rao's score test; the
// candidates the model already has drop out of C's rank). Per experiment; the family-wise
// level is kInnovationStructureLevel over the stage's tests (Bonferroni), as the regression
// test's (innovation_structure.h).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct OmittedTermTest {
  std::string experiment;
  int samples = 0;
  int rank = 0;  // of C: the test's dof; 0: not scored (the filter diverged, or memory)
  bool memory = false;  // not scored: the derivatives would exceed kOmittedTermMemory
  double statistic = std::numeric_limits<double>::quiet_NaN();  // LM
  double p_value = std::numeric_limits<double>::quiet_NaN();
  // The candidate alone with the largest statistic (g_j*^2 / C_jj), e.g. "r|r| in r'".
  std::string strongest;
  double strongest_statistic = std::numeric_limits<double>::quiet_NaN();
};

// Per experiment of a filter-error problem with process noise on a state that is not
// kinematic (not a heading or position) at its current values; empty otherwise.
// `operating_range`: problem.OperatingRange() at the same values (the states' sizes scale
// their candidates).
std::vector<OmittedTermTest> TestOmittedTerms(const OutputErrorProblem& problem,
                                              const std::vector<double>& operating_range);

// A note per test, and disturbance_absorbs_structure (per output the process noise reaches)
// naming the experiments whose p lies below the family-wise level.
void AddOmittedTermFindings(const std::string& stage, const std::vector<OmittedTermTest>& tests,
                            std::vector<std::string>* notes, std::vector<Finding>* findings);

// Whether every test was scored: where one was not, a drifting free run is not excused.
inline bool AllScored(const std::vector<OmittedTermTest>& tests) {
  for (const OmittedTermTest& t : tests) {
    if (t.rank == 0) return false;
  }
  return true;
}

}  // namespace vesselid
