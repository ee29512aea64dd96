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
  if (!relative.empty() && *relative.begin() != "..") return "";
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
