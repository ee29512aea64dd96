// Type-erased handles of the Nomoto models. Each is instantiated in its own translation unit:
// the Jet instantiations of several models in one unit exhaust the compiler's inlining budget
// and slow the integrator by 40 %.
#pragma once

#include <memory>

#include "engine/model/model_handle.h"

namespace vesselid::nomoto {

std::unique_ptr<ModelHandle> MakeFirstOrderHandle();
std::unique_ptr<ModelHandle> MakeSecondOrderHandle();
std::unique_ptr<ModelHandle> MakeNorrbinHandle();

}  // namespace vesselid::nomoto
