// A structure selection (selection_result.h) as results.json and report.txt show it: the
// folds, per candidate its cross-validated score (mean free-run fit % over the folds, its
// standard error and per-fold values), per scored output the fit % (mean, SD over folds) and
// RMSE, the estimated numbers, AIC and BIC of the fit on every run, and the choice with its
// reason.
#pragma once

#include <string>

#include "engine/run/selection_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json SelectionToJson(const SelectionResult& selection);

// The rule and the criteria, as the reports state them.
extern const char kSelectionDefinitions[];

// A report.txt section; empty for an empty selection.
std::string SelectionText(const SelectionResult& selection);

}  // namespace vesselid
