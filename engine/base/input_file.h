// Input files are opened only when they are regular files no larger than a limit. The check
// uses stat() before any open(): a directory, a named pipe (whose open() would wait for a
// writer), a device such as /dev/zero or a socket is refused by name, and a file too large
// for the run is refused before a byte of it is read.
#pragma once

#include <cstdint>
#include <string>

namespace vesselid {

// "<path>: <what is wrong>" in *error when `path` cannot be read as a `kind` (e.g. "data
// file") of at most `max_bytes`; `limit_key` names the config key of that limit, if any.
bool CheckInputFile(const std::string& path, const std::string& kind, std::uint64_t max_bytes,
                    const std::string& limit_key, std::string* error);

// "1.5 GiB", "512 KiB", "17 bytes".
std::string ByteCount(std::uint64_t bytes);

}  // namespace vesselid
