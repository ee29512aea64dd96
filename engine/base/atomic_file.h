// Files written whole or not at all: the content goes to "<path>.tmp", which is renamed onto
// the path (atomic on POSIX), so a failed or interrupted run never leaves a partial file;
// a write that fails (a full disk, a file-size limit) removes the temporary file.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace vesselid {

// Writes `content` to path via a temporary file and rename.
bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error);

// The same with the content written by `write` as it is formed (a large file never held
// whole in memory); an exception from `write` removes the temporary file and passes on.
bool WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         std::string* error);

}  // namespace vesselid
