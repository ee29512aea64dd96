// GNSS fixes as local positions: latitude and longitude (degrees, WGS84) mapped to north and
// east metres from an origin on the tangent plane there (GeographicLib::LocalCartesian, the
// east-north-up frame at height 0), so that north = x and east = y as the models use them.
// Over the few kilometres of a trial the plane departs from the ellipsoid by centimetres.
//
// A fix with latitude = longitude = 0 is a receiver without a solution (no vessel is tried at
// 0 N 0 E): it becomes a missing sample and is counted, never an origin.
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

struct GnssPositionOptions {
  std::string lat_column, lon_column;  // degrees
  bool origin_first = true;            // the first valid fix; else origin_lat/lon
  double origin_lat = 0.0, origin_lon = 0.0;
  std::string north_column = "north", east_column = "east";  // channels added (metres)
  std::string key;  // config key the options come from, for messages
};

struct GnssPositionReport {
  double origin_lat = 0.0, origin_lon = 0.0;
  std::vector<double> zero_fix_times;  // rows whose fix was 0/0
};

// Adds the north and east channels to `data` (NaN where either coordinate is missing or the
// fix is 0/0). A missing column, a latitude outside [-90, 90] or a longitude outside
// [-180, 360] is an error naming the file, line and column.
bool AddLocalPositions(const GnssPositionOptions& options, Trajectory* data,
                       GnssPositionReport* report, std::string* error);

}  // namespace vesselid
