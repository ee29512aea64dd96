#include "problems/nomoto/handles.h"
#include "problems/nomoto/second_order_rates.h"

namespace vesselid::nomoto {

std::unique_ptr<ModelHandle> MakeSecondOrderRatesHandle() {
  return MakeModelHandle(SecondOrderRates());
}

}  // namespace vesselid::nomoto
