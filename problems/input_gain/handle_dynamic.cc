#include "problems/input_gain/handles.h"

namespace vesselid::input_gain {

std::unique_ptr<ModelHandle> MakeDynamicHandle(const Bases& bases) {
  return MakeModelHandle(InputGainModel<true>(bases));
}

}  // namespace vesselid::input_gain
