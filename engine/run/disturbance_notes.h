// What a filter-error stage says of its disturbance model (model/disturbance.h): one
// disturbance_model finding naming the noise as the user reads it ("psi: sensor noise AR(1),
// tau 8.3 s, SD 0.21 deg; white 0.05 deg; process noise on eta2 ..."), with the innovations'
// whiteness per output, and the likelihood in a note.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/residual_analysis.h"
#include "engine/solve/covariance.h"

namespace vesselid {

// The disturbance in words ("psi: sensor noise AR(1), tau 8.3 s (SE 1.1), SD 0.21 deg ...").
std::string DescribeDisturbance(const OutputErrorProblem& problem, const Uncertainty& uncertainty);

// Appends the note and the finding; `innovations` the stage's innovation analyses.
void DisturbanceNotes(const std::string& stage, const OutputErrorProblem& problem,
                      const Uncertainty& uncertainty,
                      const std::vector<ResidualAnalysis>& innovations,
                      std::vector<std::string>* notes, std::vector<Finding>* findings);

}  // namespace vesselid
