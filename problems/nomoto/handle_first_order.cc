#include "problems/nomoto/handles.h"
#include "problems/nomoto/nomoto_models.h"

namespace vesselid::nomoto {

std::unique_ptr<ModelHandle> MakeFirstOrderHandle() { return MakeModelHandle(FirstOrder()); }

}  // namespace vesselid::nomoto
