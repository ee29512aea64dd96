// The eriksen2dof family for the model registry: seed 004's 2-DOF speed/yaw-rate model with
// configured basis scales, and the seed's step campaign and validation runs simulated with
// the physical planing craft (craft.h, campaign.h).
#pragma once

#include "engine/config/model_family.h"

namespace vesselid::eriksen2dof {

ModelFamily EriksenFamily();

}  // namespace vesselid::eriksen2dof
