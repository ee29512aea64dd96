// An exported model as an FMI 2.0 co-simulation FMU: a zip archive (libzip) of
// modelDescription.xml, binaries/linux64/<modelIdentifier>.so (the runtime library,
// engine/fmu/) and resources/model.json.
#pragma once

#include <string>

#include "engine/export/model_json.h"

namespace vesselid {

// The runtime library next to the running program (libvesselid_fmu.so in its folder, else in
// ../lib/vesselid/), or $VESSELID_FMU_RUNTIME; empty with a message when there is none.
std::string FindFmuRuntime(std::string* error);

// Writes `fmu_path` (replacing it whole or not at all).
bool WriteFmu(const IdentifiedModel& model, const std::string& runtime, const std::string& fmu_path,
              std::string* error);

// The FMU's GUID: a digest of its model.json text, in the 8-4-4-4-12 hex form.
std::string FmuGuid(const std::string& model_json);

}  // namespace vesselid
