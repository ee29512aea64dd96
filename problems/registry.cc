#include "problems/registry.h"

#include "problems/nomoto/nomoto_family.h"

namespace vesselid {

ModelRegistry DefaultRegistry() {
  ModelRegistry registry;
  registry.Register(nomoto::NomotoFamily());
  return registry;
}

}  // namespace vesselid
