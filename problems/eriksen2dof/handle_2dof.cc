#include "problems/eriksen2dof/handles.h"

namespace vesselid::eriksen2dof {

std::unique_ptr<ModelHandle> MakeHandle(const Model& model) { return MakeModelHandle(model); }

}  // namespace vesselid::eriksen2dof
