#include "engine/base/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vesselid {

namespace fs = std::filesystem;

bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error) {
  const std::string temporary = path + ".tmp";
  {
    errno = 0;
    std::ofstream out(temporary, std::ios::binary);
    out << content;
    out.flush();
    if (!out) {
      const int code = errno;
      out.close();
      std::error_code ignored;
      fs::remove(temporary, ignored);
      *error = path + ": write failed" + (code != 0 ? ": " + std::string(std::strerror(code)) : "");
      return false;
    }
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    *error = path + ": " + ec.message();
    return false;
  }
  return true;
}

}  // namespace vesselid
