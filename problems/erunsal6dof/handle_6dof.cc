#include "problems/erunsal6dof/handles.h"

namespace vesselid::erunsal6dof {

std::unique_ptr<ModelHandle> MakeHandle(const Model& model) { return MakeModelHandle(model); }

}  // namespace vesselid::erunsal6dof
