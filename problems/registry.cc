#include "problems/registry.h"

#include "engine/export/reference_model.h"

#include "problems/eriksen2dof/eriksen_config.h"
#include "problems/erunsal6dof/erunsal_config.h"
#include "problems/input_gain/input_gain_config.h"
#include "problems/mmg/mmg_config.h"
#include "problems/nomoto/nomoto_config.h"

namespace vesselid {

ModelRegistry DefaultRegistry() {
  ModelRegistry registry;
  registry.Register(nomoto::NomotoFamily());
  registry.Register(erunsal6dof::ErunsalFamily());
  registry.Register(input_gain::InputGainFamily());
  registry.Register(eriksen2dof::EriksenFamily());
  registry.Register(mmg::MmgFamily());
  registry.SetReferenceReader(ReadReferenceModel);
  return registry;
}

}  // namespace vesselid
