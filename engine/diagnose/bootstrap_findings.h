// Findings (bootstrap) from a regression stage's bootstrap (group_bootstrap.h), each naming the stage and
// the parameters or coefficients: a requested bootstrap that could not run; replicates that
// could not be fitted (more than 10 %); estimates whose 95 % bootstrap interval contains 0
// (not distinguishable from zero, though the estimate is not zero within 1e-12 of the
// largest bootstrapped estimate); lasso coefficients with
// unstable selection (zero in 20-80 % of the replicates).
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/run_result.h"

namespace vesselid {

void AddBootstrapFindings(const StageResult& stage, std::vector<Finding>* findings);

}  // namespace vesselid
