#include "engine/base/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace vesselid {

std::string ByteCount(std::uint64_t bytes) {
  const char* units[] = {"KiB", "MiB", "GiB", "TiB"};
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  double value = static_cast<double>(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 3) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof(text), value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

bool CheckInputFile(const std::string& path, const std::string& kind, std::uint64_t max_bytes,
                    const std::string& limit_key, std::string* error) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) {
    *error = path + ": cannot open file: " + std::strerror(errno);
    return false;
  }
  const char* not_regular = S_ISDIR(info.st_mode)    ? "a folder"
                            : S_ISFIFO(info.st_mode) ? "a named pipe"
                            : S_ISCHR(info.st_mode)  ? "a character device"
                            : S_ISBLK(info.st_mode)  ? "a block device"
                            : S_ISSOCK(info.st_mode) ? "a socket"
                            : S_ISREG(info.st_mode)  ? nullptr
                                                     : "not a regular file";
  if (not_regular != nullptr) {
    *error = path + ": is " + not_regular + ", not a " + kind + " (only regular files are read)";
    return false;
  }
  const auto bytes = static_cast<std::uint64_t>(info.st_size);
  if (bytes > max_bytes) {
    *error = path + ": the " + kind + " is " + ByteCount(bytes) + ", more than the limit of " +
             ByteCount(max_bytes) + (limit_key.empty() ? "" : " (" + limit_key + ")");
    return false;
  }
  return true;
}

}  // namespace vesselid
