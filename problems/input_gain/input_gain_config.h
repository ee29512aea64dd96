// The input-gain family for the model registry: the static or dynamic propeller variant with
// configured bases, and seed 000's campaign simulated with the physical catamaran.
#pragma once

#include "engine/config/model_family.h"

namespace vesselid::input_gain {

ModelFamily InputGainFamily();

}  // namespace vesselid::input_gain
