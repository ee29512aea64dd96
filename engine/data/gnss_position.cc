#include "engine/data/gnss_position.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "GeographicLib/LocalCartesian.hpp"

namespace vesselid {

bool AddLocalPositions(const GnssPositionOptions& options, Trajectory* data,
                       GnssPositionReport* report, std::string* error) {
  const int lat = data->Find(options.lat_column), lon = data->Find(options.lon_column);
  for (const auto& [column, name, which] :
       {std::tuple{lat, &options.lat_column, "lat"}, std::tuple{lon, &options.lon_column, "lon"}}) {
    if (column >= 0) continue;
    *error = data->source + ": no column '" + *name + "' (" + options.key + "." + which + ")";
    return false;
  }
  for (const std::string& added : {options.north_column, options.east_column}) {
    if (data->Find(added) >= 0) {
      *error = data->source + ": has a column '" + added + "' already; " + options.key +
               " adds it from the fixes";
      return false;
    }
  }
  const std::vector<double>& phi = data->columns[lat];
  const std::vector<double>& lambda = data->columns[lon];
  const size_t rows = data->t.size();
  for (size_t k = 0; k < rows; ++k) {
    for (const auto& [value, limit, column] :
         {std::tuple{phi[k], 90.0, lat}, std::tuple{lambda[k], 360.0, lon}}) {
      const double lower = column == lat ? -90.0 : -180.0;
      if (std::isnan(value) || (value >= lower && value <= limit)) continue;
      char text[200];
      std::snprintf(text, sizeof(text), ":%d: column '%s': %.10g is not a %s (outside [%g, %g])",
                    k < data->line.size() ? data->line[k] : static_cast<int>(k) + 2,
                    data->names[column].c_str(), value, column == lat ? "latitude" : "longitude",
                    lower, limit);
      *error = data->source + text;
      return false;
    }
  }
  GnssPositionReport result;
  auto valid = [&](size_t k) {
    return !std::isnan(phi[k]) && !std::isnan(lambda[k]) && !(phi[k] == 0.0 && lambda[k] == 0.0);
  };
  if (options.origin_first) {
    size_t k = 0;
    while (k < rows && !valid(k)) ++k;
    if (k == rows) {
      *error = data->source + ": no valid fix in columns '" + options.lat_column + "' and '" +
               options.lon_column + "' (" + options.key + ")";
      return false;
    }
    result.origin_lat = phi[k];
    result.origin_lon = lambda[k];
  } else {
    result.origin_lat = options.origin_lat;
    result.origin_lon = options.origin_lon;
  }
  const GeographicLib::LocalCartesian plane(result.origin_lat, result.origin_lon, 0.0);
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> north(rows, kNaN), east(rows, kNaN);
  for (size_t k = 0; k < rows; ++k) {
    if (!std::isnan(phi[k]) && !std::isnan(lambda[k]) && !valid(k)) {
      result.zero_fix_times.push_back(data->t[k]);
    }
    if (!valid(k)) continue;
    double up = 0.0;
    plane.Forward(phi[k], lambda[k], 0.0, east[k], north[k], up);
  }
  data->names.push_back(options.north_column);
  data->columns.push_back(std::move(north));
  data->names.push_back(options.east_column);
  data->columns.push_back(std::move(east));
  *report = std::move(result);
  return true;
}

}  // namespace vesselid
