// Bootstrap standard errors of a step regression (group_bootstrap.h): the strata are the
// damping samples' groups (steady states of one record's input levels with their mirrored
// copies, shared by sigma_0 and sigma_1) and each inertia set's groups (steps), the groups the
// leave-one-group-out CV leaves out. The samples are extracted once (window and step fits are
// held); a replicate regresses every term again on the drawn groups, a group drawn twice
// entering twice:
//
//   hold_lambda (default): the full fit's normalisation, lambda and asymptote (a, b) held,
//     the lasso refitted at that lambda (the common choice: it measures the sampling spread
//     of the coefficients, not of the tuning; selecting them again makes a replicate ~100
//     times dearer and its spread includes the grid's jumps);
//   otherwise: the whole regression (normalisation, CV path, (a, b) grid) on the replicate,
//     the copies of a group as distinct CV groups; a and b are then bootstrapped too.
//
// Quantities: every estimated form parameter (model names; a, b only when re-selected). Zero
// share: every penalised lasso coefficient on the normalised basis, named by the model
// parameter of the same monomial ("sigma_U.U2", "m_U.tanh").
#pragma once

#include <string>
#include <vector>

#include "engine/model/damping_inertia_form.h"
#include "engine/regression/group_bootstrap.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// `report`: RunStepRegression's with `options`; `parameter_names` the model's.
bool BootstrapStepRegression(const DampingInertiaForm& form, const StepRegressionReport& report,
                             const StepRegressionOptions& options,
                             const std::vector<std::string>& parameter_names,
                             BootstrapSummary* bootstrap, std::string* error);

}  // namespace vesselid
