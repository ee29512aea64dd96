#include "engine/config/data_folder.h"

#include <filesystem>

namespace vesselid {

std::string OutsideDataFolder(const std::string& file, const std::string& folder,
                              const WorkLimits& limits) {
  namespace fs = std::filesystem;
  if (limits.outside_data) return "";
  std::error_code ec;
  const fs::path root =
      fs::absolute(folder.empty() ? fs::path(".") : fs::path(folder), ec).lexically_normal();
  const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : root / file;
  const fs::path relative = path.lexically_normal().lexically_relative(root);
  if (!relative.empty() && *relative.begin() != "..") return "";
  return "'" + file + "' is outside the data folder " + root.string() +
         " (--data, else the config's folder): give --data a folder that holds it, or allow "
         "files outside with limits: {outside_data: true}";
}

}  // namespace vesselid
