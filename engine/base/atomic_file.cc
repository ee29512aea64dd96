#include "engine/base/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vesselid {

namespace fs = std::filesystem;

bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error) {
  return WriteFileAtomically(path, [&content](std::ostream& out) { out << content; }, error);
}

bool WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         std::string* error) {
  const std::string temporary = path + ".tmp";
  {
    // Whatever is at the temporary's name goes first (a link planted there is removed, never
    // written through), so that the file opened is a new one.
    std::error_code removed;
    fs::remove(temporary, removed);
    errno = 0;
    std::ofstream out(temporary, std::ios::binary);
    try {
      write(out);
    } catch (...) {
      out.close();
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw;
    }
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
