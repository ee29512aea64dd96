// The one-standard-error rule of model-structure selection (Hastie, Tibshirani & Friedman,
// The Elements of Statistical Learning, 2nd ed., §7.10): of the candidates whose
// cross-validated score is within one standard error of the best score, choose the simplest.
#pragma once

#include "engine/run/selection_result.h"

namespace vesselid {

// Sets best (the highest score), within_one_se (score >= best.score - best.score_se) and
// chosen (the smallest complexity among those, then the higher score, then the earlier
// candidate) with the reason stated; chosen stays -1 when no candidate is usable.
void ChooseByOneStandardError(SelectionResult* result);

}  // namespace vesselid
