// Findings and one-line descriptions from the residual analysis of a stage (residual_analysis.h):
// a channel whose residuals are coloured breaks the assumption of the Hessian standard errors
// s^2 (J^T J)^-1 (white residuals), which are then too narrow; residuals correlated with past
// inputs point at dynamics the model leaves out (or noise on a measured input).
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/run_result.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

// "coloured (lag-1 0.93, Ljung-Box p < 1e-16)", "white (lag-1 0.01, p 0.42)", or
// "not tested (8 samples)"; with ", correlated with past delta" when input-correlated and
// ", irregular sampling (intervals vary 35 %)" when so.
std::string DescribeResiduals(const ResidualAnalysis& a);

// The warning for one stage's output whose residuals are coloured in `coloured` of its
// `analysed` experiments (the worst, largest |lag-1|, named first, at most six), with what it
// means for the stage's standard errors: too narrow when `uncertainty` is the Hessian's (and
// by how much the HAC beside it says), allowed for when it is the HAC's.
std::string ColouredResidualWarning(const std::string& stage, const std::string& output,
                                    const std::vector<const ResidualAnalysis*>& coloured,
                                    int analysed, const Uncertainty& uncertainty);

// The warning for one stage's output whose residuals are correlated with past inputs.
std::string InputCorrelatedResidualWarning(const std::string& stage, const std::string& output,
                                           const std::vector<const ResidualAnalysis*>& correlated,
                                           int analysed);

// Appends the stage's residual findings, one per output and kind with the count of its
// experiments; channels of noise-free data (ResidualAnalysis::noise_free) and of failed fits
// (FitFailed, a finding of their own) are left out.
void AddResidualFindings(const StageResult& stage, std::vector<Finding>* findings);

}  // namespace vesselid
