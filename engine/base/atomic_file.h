// Files written whole or not at all: the content goes to "<path>.tmp", which is renamed onto
// the path (atomic on POSIX), so a failed or interrupted run never leaves a partial file;
// a write that fails (a full disk, a file-size limit) removes the temporary file.
#pragma once

#include <string>

namespace vesselid {

// Writes `content` to path via a temporary file and rename.
bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error);

}  // namespace vesselid
