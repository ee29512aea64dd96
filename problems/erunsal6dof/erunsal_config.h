// The Erunsal 6-DOF family for the model registry: the model with known constants and an
// active DOF set from the config, and the seed 002 test campaign simulator.
#pragma once

#include "engine/config/model_family.h"

namespace vesselid::erunsal6dof {

ModelFamily ErunsalFamily();

}  // namespace vesselid::erunsal6dof
