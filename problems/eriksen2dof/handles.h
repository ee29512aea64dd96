// The type-erased handle of the Eriksen-Breivik model, instantiated in its own translation
// unit (the Jet instantiations are heavy).
#pragma once

#include <memory>

#include "engine/model/model_handle.h"
#include "problems/eriksen2dof/eriksen_model.h"

namespace vesselid::eriksen2dof {

std::unique_ptr<ModelHandle> MakeHandle(const Model& model);

}  // namespace vesselid::eriksen2dof
