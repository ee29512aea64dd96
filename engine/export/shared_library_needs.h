// The shared libraries a shared library asks the dynamic loader for (its DT_NEEDED entries):
// what the FMU's runtime needs on the machine that loads it, stated in the FMU's documentation.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

// The DT_NEEDED names of the 64-bit ELF file at `path`, in their order; false with a message
// when it is not one or cannot be read.
bool SharedLibraryNeeds(const std::string& path, std::vector<std::string>* needs,
                        std::string* error);

}  // namespace vesselid
