// The twin-thruster field log (field_log.h) made from a short quadratic-thrust USV campaign:
// rows jittered within +-30 ms and in order, heading in compass degrees, GNSS fixes at half the
// row rate whose latitude and longitude map back onto the campaign's north/east (checked by
// the forward conversion geodetic -> ECEF -> local tangent plane, written here independently),
// and the defects where they were asked for.
#include "problems/input_gain/field_log.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "engine/config/config.h"
#include "gtest/gtest.h"
#include "problems/input_gain/campaign.h"
#include "problems/registry.h"

namespace vesselid {
namespace field_log_test {

using namespace input_gain;

// Local north/east (m) of (lat, lon) on the WGS84 tangent plane at (lat0, lon0).
void GeodeticToLocal(double lat0, double lon0, double lat, double lon, double* north,
                     double* east) {
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f), d = M_PI / 180.0;
  auto ecef = [&](double phi, double lambda, double out[3]) {
    const double n = a / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
    out[0] = n * std::cos(phi) * std::cos(lambda);
    out[1] = n * std::cos(phi) * std::sin(lambda);
    out[2] = n * (1.0 - e2) * std::sin(phi);
  };
  double p0[3], p[3];
  ecef(lat0 * d, lon0 * d, p0);
  ecef(lat * d, lon * d, p);
  const double dx = p[0] - p0[0], dy = p[1] - p0[1], dz = p[2] - p0[2];
  const double sp = std::sin(lat0 * d), cp = std::cos(lat0 * d);
  const double sl = std::sin(lon0 * d), cl = std::cos(lon0 * d);
  *east = -sl * dx + cl * dy;
  *north = -sp * cl * dx - sp * sl * dy + cp * dz;
}

TEST(FieldLog, GeodeticPositionsRoundTrip) {
  for (const double north : {-800.0, 0.0, 350.0}) {
    for (const double east : {-600.0, 1.0, 900.0}) {
      double lat, lon, n, e;
      LocalToGeodetic(63.44, 10.40, north, east, &lat, &lon);
      GeodeticToLocal(63.44, 10.40, lat, lon, &n, &e);
      // The point lies on the tangent plane, (d^2 / 2R) above the ellipsoid: the
      // horizontal error of dropping that height is far below a millimetre.
      EXPECT_NEAR(n, north, 1e-3);
      EXPECT_NEAR(e, east, 1e-3);
    }
  }
  double lat, lon;
  LocalToGeodetic(63.44, 10.40, 111.0, 0.0, &lat, &lon);
  EXPECT_NEAR(lat - 63.44, 111.0 / 111'470.0, 2e-6);  // ~111.47 km per degree at 63.4 N
}

TEST(FieldLog, JitterDegreesGeodeticFixesAndDefects) {
  CampaignOptions campaign;
  campaign.segments = 5;
  campaign.total_duration = 150.0;
  campaign.min_segment = 25.0;
  campaign.max_segment = 35.0;
  campaign.seed = 4;
  campaign.step = kFieldLogCampaignStep;
  campaign.gnss_period = campaign.ahrs_period = campaign.step;
  campaign.gnss_offset = 0.0;
  campaign.truth_columns = false;
  Trajectory dense, log;
  std::string error;
  ASSERT_TRUE(SimulateCampaign(QuadraticUsvParameters(), campaign, &dense, &error)) << error;
  FieldLogOptions options;
  options.zero_fix_segment = 1;
  options.stale_segment = 2;
  options.stale_fixes = 4;
  options.short_segment = 3;
  ASSERT_TRUE(MakeFieldLog(dense, options, 7, &log, &error)) << error;
  ASSERT_EQ(log.names,
            (std::vector<std::string>{"segment", "lat", "lon", "heading", "pwm_L", "pwm_R"}));
  std::map<double, size_t> dense_row;
  for (size_t i = 0; i < dense.t.size(); ++i) dense_row[dense.t[i]] = i;
  const int n = dense.Find("n"), e = dense.Find("e"), heading = dense.Find("heading");
  std::map<int, double> first_command;  // per segment: its ticks start here
  for (size_t i = 0; i < dense.t.size(); ++i) {
    const int segment = static_cast<int>(dense.columns[dense.Find("segment")][i]);
    if (!first_command.count(segment) && std::isfinite(dense.columns[dense.Find("pwm_L")][i])) {
      first_command[segment] = dense.t[i];
    }
  }

  std::map<int, int> rows, zero_fixes, longest_repeat;
  std::map<int, double> first_t, last_t;
  double largest_jitter = 0.0;
  int repeat = 0;
  for (size_t k = 0; k < log.t.size(); ++k) {
    const int segment = static_cast<int>(log.columns[0][k]);
    if (k > 0) {
      ASSERT_GT(log.t[k], log.t[k - 1]);
    }
    if (!first_t.count(segment)) first_t[segment] = log.t[k];
    last_t[segment] = log.t[k];
    // Nominal ticks 0.1 s apart from the segment's first command: the offset is the jitter.
    const int index = rows[segment]++;
    const double tick = first_command[segment] + 0.1 * index;
    largest_jitter = std::max(largest_jitter, std::abs(log.t[k] - tick));
    const auto at = dense_row.find(log.t[k]);
    ASSERT_NE(at, dense_row.end()) << "row time " << log.t[k] << " is not a campaign sample";
    const size_t i = at->second;
    const double degrees = log.columns[3][k];
    ASSERT_TRUE(degrees >= 0.0 && degrees < 360.0);
    EXPECT_NEAR(std::remainder(degrees - dense.columns[heading][i] * 180.0 / M_PI, 360.0), 0.0,
                1e-9);
    EXPECT_TRUE(std::isfinite(log.columns[4][k]) && std::isfinite(log.columns[5][k]));
    const double lat = log.columns[1][k], lon = log.columns[2][k];
    EXPECT_EQ(std::isfinite(lat), index % 2 == 0) << "GNSS on every other row";
    if (!std::isfinite(lat)) continue;
    if (lat == 0.0 && lon == 0.0) {
      ++zero_fixes[segment];
      continue;
    }
    size_t previous = k - 2;  // the previous fix of the segment
    if (index >= 2 && log.columns[1][previous] == lat && log.columns[2][previous] == lon) {
      longest_repeat[segment] = std::max(longest_repeat[segment], ++repeat);
      continue;
    }
    repeat = 0;
    double north, east;
    GeodeticToLocal(options.origin_lat, options.origin_lon, lat, lon, &north, &east);
    EXPECT_NEAR(north, dense.columns[n][i], 1e-3);
    EXPECT_NEAR(east, dense.columns[e][i], 1e-3);
  }
  // +-30 ms (0.005 s quantised), a logger's tick-to-tick spread rather than none.
  EXPECT_LE(largest_jitter, 0.03 + 1e-9);
  EXPECT_GE(largest_jitter, 0.025 - 1e-9);
  EXPECT_EQ(rows.size(), 5u);
  EXPECT_EQ(zero_fixes, (std::map<int, int>{{1, 1}}));
  EXPECT_EQ(longest_repeat, (std::map<int, int>{{2, 4}}));
  EXPECT_LT(last_t[3] - first_t[3], 2.0 + 0.03);
  EXPECT_GE(rows[3], 19);
  EXPECT_LE(rows[3], 20);
  for (const int segment : {0, 1, 2, 4}) EXPECT_GT(last_t[segment] - first_t[segment], 20.0);
}

TEST(FieldLog, OptionsAreChecked) {
  FieldLogOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.jitter = 0.06;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("jitter"), std::string::npos);
  options = FieldLogOptions();
  options.short_segment = options.stale_segment = 2;
  EXPECT_FALSE(options.IsValid(&error));
  options = FieldLogOptions();
  options.origin_lat = 91.0;
  EXPECT_FALSE(options.IsValid(&error));
}

// The simulation section's `field_log` map: a bad value names the file, line and key.
TEST(FieldLog, ConfigRefusalsNameFileLineAndKey) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "vesselid_field_log_config";
  fs::create_directories(dir);
  const ModelRegistry registry = DefaultRegistry();
  std::ofstream data(dir / "data.csv");
  data << "t,n,e,heading,pwm_L,pwm_R\n";
  for (int k = 0; k < 20; ++k) data << 0.1 * k << "," << 0.1 * k << ",0,0,0.5,0.5\n";
  data.close();
  auto refusal = [&](const std::string& field_log) {
    std::ofstream(dir / "config.yaml")
        << "model: {family: input_gain}\nsimulation:\n  file: log.csv\n  segments: 4\n"
        << "  duration_min: 2\n  segment_s: [20, 40]\n  field_log: " << field_log << "\n"
        << "experiments:\n  - {name: log, file: data.csv, inputs: {u_L: pwm_L, u_R: pwm_R},\n"
        << "     outputs: {n: n, e: e, psi: heading}}\n"
        << "stages:\n  - {name: fit, parameters: {b_u: 0.3}}\n";
    ConfigFile config;
    std::string error;
    if (!LoadConfigFile((dir / "config.yaml").string(), "", registry, &config, &error)) {
      return error;
    }
    return SimulateConfig(config, dir.string(), &error, true) ? std::string() : error;
  };
  EXPECT_NE(refusal("{jitter_ms: 80}")
                .find("config.yaml:7: simulation.field_log: field log: "
                      "jitter must be"),
            std::string::npos)
      << refusal("{jitter_ms: 80}");
  EXPECT_NE(refusal("{short_segment: 4}")
                .find("simulation.field_log.short_segment: segment 4 "
                      "of 4"),
            std::string::npos)
      << refusal("{short_segment: 4}");
  EXPECT_NE(refusal("{origin: [63.4]}").find("simulation.field_log.origin: expected [lat, lon]"),
            std::string::npos);
  EXPECT_NE(refusal("{jiter_ms: 3}").find("config.yaml:7"), std::string::npos)
      << refusal("{jiter_ms: 3}");
  EXPECT_EQ(refusal("{rate: 10, jitter_ms: 30, zero_fix_segment: 1}"), "");
  fs::remove_all(dir);
}

}  // namespace field_log_test
}  // namespace vesselid
