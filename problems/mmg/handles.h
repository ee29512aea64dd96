// Type-erased handle of the MMG model, in its own translation unit (problems/README.md).
#pragma once

#include <memory>

#include "engine/model/model_handle.h"
#include "problems/mmg/mmg_model.h"

namespace vesselid::mmg {

std::unique_ptr<ModelHandle> MakeMmgHandle(const Ship& ship);

}  // namespace vesselid::mmg
