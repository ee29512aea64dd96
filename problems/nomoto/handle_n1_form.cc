#include "problems/nomoto/handles.h"
#include "problems/nomoto/n1_form_models.h"

namespace vesselid::nomoto {

std::unique_ptr<ModelHandle> MakeN1FormHandle(bool cubic, double length) {
  N1Form model;
  model.cubic = cubic;
  model.length = length;
  return MakeModelHandle(model);
}

}  // namespace vesselid::nomoto
