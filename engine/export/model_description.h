// modelDescription.xml of an exported model's FMI 2.0 co-simulation FMU: its variables in the
// layout of fmu_layout.h, the model's SI units, every parameter tunable at the run's value,
// `ensemble_member` (0 the estimate, k the k-th draw), and the model structure (every output
// an initial unknown). `guid` ties it to the model.json it is packed with.
#pragma once

#include <string>

#include "engine/export/model_json.h"

namespace vesselid {

inline constexpr char kFmuModelIdentifier[] = "vesselid_model";

std::string ModelDescriptionXml(const IdentifiedModel& model, const std::string& guid);

}  // namespace vesselid
