#include "problems/input_gain/handles.h"

namespace vesselid::input_gain {

std::unique_ptr<ModelHandle> MakeDynamicHandle(const Bases& bases, const ThrustLaw& law) {
  return MakeModelHandle(InputGainModel<true>(bases, law));
}

}  // namespace vesselid::input_gain
