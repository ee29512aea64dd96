// The Nomoto steering family for the model registry: model types first_order, second_order,
// norrbin, and the seed 003 closed-loop experiment simulator.
#pragma once

#include "engine/config/model_family.h"

namespace vesselid::nomoto {

ModelFamily NomotoFamily();

}  // namespace vesselid::nomoto
