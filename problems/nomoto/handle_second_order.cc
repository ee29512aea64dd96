#include "problems/nomoto/handles.h"
#include "problems/nomoto/nomoto_models.h"

namespace vesselid::nomoto {

std::unique_ptr<ModelHandle> MakeSecondOrderHandle() { return MakeModelHandle(SecondOrder()); }

}  // namespace vesselid::nomoto
