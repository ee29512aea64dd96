// Type-erased handle of the 6-DOF model (instantiated in its own translation unit).
#pragma once

#include <memory>

#include "engine/model/model_handle.h"
#include "problems/erunsal6dof/erunsal_model.h"

namespace vesselid::erunsal6dof {

std::unique_ptr<ModelHandle> MakeHandle(const Model& model);

}  // namespace vesselid::erunsal6dof
