#include "problems/input_gain/handles.h"

namespace vesselid::input_gain {

std::unique_ptr<ModelHandle> MakeStaticHandle(const Bases& bases) {
  return MakeModelHandle(InputGainModel<false>(bases));
}

}  // namespace vesselid::input_gain
