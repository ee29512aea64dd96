#include "engine/config/data_folder.h"

#include <filesystem>

namespace vesselid {

std::string DataFolderLeft(const std::string& file, const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path root =
      fs::absolute(folder.empty() ? fs::path(".") : fs::path(folder), ec).lexically_normal();
  const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : root / file;
  const fs::path relative = path.lexically_normal().lexically_relative(root);
  if (relative.empty() || *relative.begin() == "..") return root.string();
  // Inside by its name; inside by what it is too: a link in the folder to a file or folder
  // elsewhere leaves it like "../" does (both sides resolved, so a data folder reached through
  // a link of its own stays itself).
  const fs::path real_root = fs::weakly_canonical(root, ec);
  if (ec) return "";
  const fs::path real = fs::weakly_canonical(path, ec);
  if (ec) return "";
  const fs::path real_relative = real.lexically_relative(real_root);
  if (!real_relative.empty() && *real_relative.begin() != "..") return "";
  return root.string();
}

std::string OutsideDataFolder(const std::string& file, const std::string& folder,
                              const WorkLimits& limits) {
  const std::string left = DataFolderLeft(file, folder);
  if (left.empty() || limits.outside_data) return "";
  return "'" + file + "' is outside the data folder " + left +
         " (--data, else the config's folder): give --data a folder that holds it, or allow "
         "files outside with limits: {outside_data: true}";
}

}  // namespace vesselid
