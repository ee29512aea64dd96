#include "problems/input_gain/handles.h"

namespace vesselid::input_gain {

std::unique_ptr<ModelHandle> MakeStaticHandle(const Bases& bases, const ThrustLaw& law) {
  return MakeModelHandle(InputGainModel<false>(bases, law));
}

}  // namespace vesselid::input_gain
