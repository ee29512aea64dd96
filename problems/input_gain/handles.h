// Type-erased handles of the input-gain model variants, each in its own translation unit
// (see nomoto/handles.h for why).
#pragma once

#include <memory>

#include "engine/model/model_handle.h"
#include "problems/input_gain/input_gain_model.h"

namespace vesselid::input_gain {

std::unique_ptr<ModelHandle> MakeStaticHandle(const Bases& bases,
                                              const ThrustLaw& law = ThrustLaw());
std::unique_ptr<ModelHandle> MakeDynamicHandle(const Bases& bases,
                                               const ThrustLaw& law = ThrustLaw());

}  // namespace vesselid::input_gain
