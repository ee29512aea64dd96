// documentation/index.html of an exported FMU (FMI 2.0, section 2.3: the documentation's entry
// point): the model, its parameters with their values and standard errors, and the shared
// libraries the FMU's binary needs on the machine that loads it.
#pragma once

#include <string>
#include <vector>

#include "engine/export/model_json.h"

namespace vesselid {

// `needs`: the binary's DT_NEEDED libraries (shared_library_needs.h).
std::string FmuDocumentationHtml(const IdentifiedModel& model, const std::vector<std::string>& needs);

}  // namespace vesselid
