#include "engine/output/folder_exchange.h"

#include <fcntl.h>
#include <stdio.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace vesselid {

namespace fs = std::filesystem;

bool ExchangeFolders(const std::string& a, const std::string& b, std::string* error) {
  if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return true;
  *error = a + " and " + b + ": cannot exchange: " + std::strerror(errno);
  return false;
}

bool SomeoneWorksInside(const std::string& folder) {
  const fs::path inside(folder);
  std::error_code ec;
  for (auto it = fs::directory_iterator("/proc", ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string pid = it->path().filename().string();
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::error_code link_ec;  // another user's process, or one that ended: not readable
    const fs::path cwd = fs::read_symlink(it->path() / "cwd", link_ec);
    if (link_ec) continue;
    const fs::path relative = cwd.lexically_relative(inside);
    if (!relative.empty() && *relative.begin() != "..") return true;
  }
  return false;
}

}  // namespace vesselid
