// Bootstrap standard errors of a least-squares stage (group_bootstrap.h), for the lasso (whose
// regressions have no covariance) and on request for plain or ridge regressions beside their
// analytic ones. The groups are contiguous blocks: every record's used samples, concatenated
// in record order, cut into `blocks` blocks of equal size (neighbouring samples share their
// smoothing window and their unmodelled disturbance, so whole blocks are drawn). A replicate
// reruns the whole procedure of RunLeastSquares (profile search, regressions, minimum
// distance) with each sample counted as often as its block was drawn; with `hold_lambda` each
// equation's penalty keeps the lambda the full fit selected, otherwise its cross-validation
// runs again on the replicate.
//
// Bootstrapped: every estimated parameter the full fit determines (name as the model's, a
// per-experiment one as "name[experiment]"; a parameter searched inside the regressors too,
// which has no analytic SE); with the lasso, the zero share of every regressed coefficient
// ("<state>': <coefficient>"). A replicate in which a parameter becomes undetermined (its
// experiment or region was not drawn) counts as failed.
#pragma once

#include <string>
#include <vector>

#include "engine/regression/group_bootstrap.h"
#include "engine/regression/least_squares.h"

namespace vesselid {

// `fit` and `summary`: RunLeastSquares' output on `records` with `options`.
bool BootstrapLeastSquares(const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                           const LeastSquaresOptions& options,
                           const std::vector<RegressionRecord>& records,
                           const LeastSquaresResult& fit, const LeastSquaresSummary& summary,
                           BootstrapSummary* bootstrap, std::string* error);

}  // namespace vesselid
