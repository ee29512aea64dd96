#include "problems/mmg/handles.h"

namespace vesselid::mmg {

std::unique_ptr<ModelHandle> MakeMmgHandle(const Ship& ship) {
  Model model;
  model.ship = ship;
  return MakeModelHandle(model);
}

}  // namespace vesselid::mmg
