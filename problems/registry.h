// Every model family the vesselid binary knows, in one registry.
#pragma once

#include "engine/config/model_registry.h"

namespace vesselid {

ModelRegistry DefaultRegistry();

}  // namespace vesselid
