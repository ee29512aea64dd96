// Latitude/longitude to local north/east metres (gnss_position.h), checked against
// GeographicLib's geodesic distances and the WGS84 radii of curvature.
#include "engine/data/gnss_position.h"

#include <cmath>

#include "GeographicLib/Geodesic.hpp"
#include "gtest/gtest.h"

namespace vesselid {
namespace gnss_position_test {

Trajectory Fixes(const std::vector<double>& lat, const std::vector<double>& lon) {
  Trajectory data;
  data.source = "log.csv";
  for (size_t k = 0; k < lat.size(); ++k) {
    data.t.push_back(0.2 * k);
    data.line.push_back(static_cast<int>(k) + 2);
  }
  data.names = {"lat", "lon"};
  data.columns = {lat, lon};
  return data;
}

GnssPositionOptions Options() {
  GnssPositionOptions o;
  o.lat_column = "lat";
  o.lon_column = "lon";
  o.key = "experiments[0].position";
  return o;
}

TEST(GnssPosition, KnownDistancesAt63North) {
  const double kNaN = std::nan("");
  Trajectory data =
      Fixes({63.43, 63.431, 63.43, 63.4305, kNaN}, {10.39, 10.39, 10.391, 10.3905, 10.39});
  GnssPositionReport report;
  std::string error;
  ASSERT_TRUE(AddLocalPositions(Options(), &data, &report, &error)) << error;
  const std::vector<double>& north = data.columns[data.Find("north")];
  const std::vector<double>& east = data.columns[data.Find("east")];
  EXPECT_EQ(report.origin_lat, 63.43);
  EXPECT_EQ(north[0], 0.0);
  EXPECT_EQ(east[0], 0.0);
  // 0.001 deg of latitude: the meridian radius M = a (1 - e^2) / (1 - e^2 sin^2 phi)^1.5 at
  // 63.43 N gives 111.47 m; of longitude: N cos(phi) gives 49.93 m.
  EXPECT_NEAR(north[1], 111.468, 0.01);
  EXPECT_NEAR(east[1], 0.0, 1e-6);
  EXPECT_NEAR(east[2], 49.926, 0.01);
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  for (int k : {1, 2, 3}) {
    double distance = 0.0;
    wgs84.Inverse(63.43, 10.39, data.columns[0][k], data.columns[1][k], distance);
    EXPECT_NEAR(std::hypot(north[k], east[k]), distance, 1e-3 * distance / 100.0) << k;
  }
  EXPECT_TRUE(std::isnan(north[4]) && std::isnan(east[4]));
}

TEST(GnssPosition, ZeroFixesAreMissingAndNeverTheOrigin) {
  Trajectory data = Fixes({0.0, 63.43, 0.0, 63.431}, {0.0, 10.39, 0.0, 10.39});
  GnssPositionReport report;
  std::string error;
  ASSERT_TRUE(AddLocalPositions(Options(), &data, &report, &error)) << error;
  EXPECT_EQ(report.origin_lat, 63.43);
  EXPECT_EQ(report.zero_fix_times, (std::vector<double>{0.0, 0.4}));
  const std::vector<double>& north = data.columns[data.Find("north")];
  EXPECT_TRUE(std::isnan(north[0]) && std::isnan(north[2]));
  EXPECT_NEAR(north[3], 111.468, 0.01);
}

TEST(GnssPosition, GivenOrigin) {
  Trajectory data = Fixes({63.43, 63.431}, {10.39, 10.39});
  GnssPositionOptions options = Options();
  options.origin_first = false;
  options.origin_lat = 63.431;
  options.origin_lon = 10.39;
  GnssPositionReport report;
  std::string error;
  ASSERT_TRUE(AddLocalPositions(options, &data, &report, &error)) << error;
  EXPECT_NEAR(data.columns[data.Find("north")][0], -111.468, 0.01);
  EXPECT_NEAR(data.columns[data.Find("north")][1], 0.0, 1e-9);
}

TEST(GnssPosition, BadInputNamesFileLineColumnOrKey) {
  GnssPositionReport report;
  std::string error;
  Trajectory data = Fixes({63.43, 93.5}, {10.39, 10.39});
  EXPECT_FALSE(AddLocalPositions(Options(), &data, &report, &error));
  EXPECT_EQ(error, "log.csv:3: column 'lat': 93.5 is not a latitude (outside [-90, 90])");
  data = Fixes({63.43, 63.43}, {10.39, -200});
  EXPECT_FALSE(AddLocalPositions(Options(), &data, &report, &error));
  EXPECT_NE(error.find("log.csv:3: column 'lon': -200 is not a longitude"), std::string::npos);
  data = Fixes({63.43}, {10.39});
  data.names[0] = "latitude";
  EXPECT_FALSE(AddLocalPositions(Options(), &data, &report, &error));
  EXPECT_EQ(error, "log.csv: no column 'lat' (experiments[0].position.lat)");
  data = Fixes({0.0, 0.0}, {0.0, 0.0});
  EXPECT_FALSE(AddLocalPositions(Options(), &data, &report, &error));
  EXPECT_NE(error.find("no valid fix"), std::string::npos);
}

}  // namespace gnss_position_test
}  // namespace vesselid
