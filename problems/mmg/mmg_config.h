// The mmg family for the model registry: the MMG standard 3-DOF manoeuvring model
// (mmg_model.h) with the ship's dimensions as given data, and the KVLCC2-like free-running
// campaign (campaign.h) it simulates.
#pragma once

#include "engine/config/model_family.h"

namespace vesselid::mmg {

ModelFamily MmgFamily();

}  // namespace vesselid::mmg
