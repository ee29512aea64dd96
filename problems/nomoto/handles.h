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
// Norrbin's n1-form (n1_form_models.h): first order, or with the cubic n3 term; length > 0
// makes the parameters non-dimensional and adds the speed input U.
std::unique_ptr<ModelHandle> MakeN1FormHandle(bool cubic, double length = 0.0);
std::unique_ptr<ModelHandle> MakeSecondOrderRatesHandle();

}  // namespace vesselid::nomoto
