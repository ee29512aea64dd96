// Estimates that compensate each other: when two free parameters of a stage have
// |correlation| > kCompensationCorrelation, the data determine only a combination of them and
// each value is an artefact of the other (a quadratic thrust law on a purely quadratic
// thruster drives k_f up and b_u down at correlation -1). One warning per group of estimates
// linked by such pairs names them and the (strongest) correlation and suggests the one to drop
// or fix: the one whose removal the data support, i.e. with the largest relative standard
// error, plus the model's own hint (ModelInfo::compensation_hints).
#pragma once

#include <string>
#include <vector>

#include "engine/model/model.h"
#include "engine/run/run_result.h"

namespace vesselid {

inline constexpr double kCompensationCorrelation = 0.999;
// A pair whose relative standard errors are both below this is determined despite its
// correlation (noise-free data) and not reported.
inline constexpr double kCompensationRelativeError = 0.01;

// Appends "<where>b_u and k_f compensate each other ..." lines for `stage` to `warnings`;
// initial states and per-experiment values are left to the correlation matrix.
void AddCompensationWarnings(const ModelInfo& info, const StageResult& stage,
                             const std::string& where, std::vector<std::string>* warnings);

// " (hint)" for the parameter a note begins with ("d_f is at its upper bound ..."), or "".
std::string StructureHint(const ModelInfo& info, const std::string& note);

}  // namespace vesselid
