#include "problems/eriksen2dof/handle.h"

namespace vesselid::eriksen2dof {

std::unique_ptr<ModelHandle> MakeHandle(const Model& model) { return MakeModelHandle(model); }

}  // namespace vesselid::eriksen2dof
