#include "problems/input_gain/field_log.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "engine/base/nan.h"

namespace vesselid::input_gain {
namespace {

constexpr double kDegree = M_PI / 180.0;
constexpr int kZeroFix = 10;    // the zero fix is a segment's 11th (2 s in at 5 Hz)
constexpr int kStaleFrom = 20;  // the stale fixes follow a segment's 20th (4 s in)

enum TrackColumn { kTrackSegment, kTrackNorth, kTrackEast, kTrackHeading, kTrackPwmL, kTrackPwmR };
const char* const kCampaignNames[] = {"segment", "n", "e", "heading", "pwm_L", "pwm_R"};
enum LogColumn { kLogSegment, kLat, kLon, kLogHeading, kLogPwmL, kLogPwmR, kLogColumns };
const char* const kLogNames[] = {"segment", "lat", "lon", "heading", "pwm_L", "pwm_R"};

}  // namespace

bool FieldLogOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    *error = "field log: " + message;
    return false;
  };
  if (!(std::abs(origin_lat) <= 85.0 && std::abs(origin_lon) <= 180.0)) {
    return fail("origin must be [lat, lon] in degrees with |lat| <= 85, |lon| <= 180");
  }
  if (!(rate > 0.0 && rate <= 100.0)) return fail("rate must be in (0, 100] Hz");
  if (!(jitter >= 0.0 && 2.0 * jitter < 1.0 / rate)) {
    return fail("jitter must be >= 0 and below half the row interval (rows stay in order)");
  }
  if (!(stale_fixes >= 1 && stale_fixes <= 50)) return fail("stale_fixes must be in [1, 50]");
  if (!(short_s > 0.0)) return fail("short_s must be positive");
  if (short_segment >= 0 && (short_segment == zero_fix_segment || short_segment == stale_segment)) {
    return fail("the short segment must not also hold the zero fix or the stale fixes");
  }
  return true;
}

void LocalToGeodetic(double lat0, double lon0, double north, double east, double* lat,
                     double* lon) {
  constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double sp = std::sin(lat0 * kDegree), cp = std::cos(lat0 * kDegree);
  const double sl = std::sin(lon0 * kDegree), cl = std::cos(lon0 * kDegree);
  const double n0 = a / std::sqrt(1.0 - e2 * sp * sp);
  // ECEF of the origin plus the tangent-plane offset (up = 0).
  const double x = n0 * cp * cl - sl * east - sp * cl * north;
  const double y = n0 * cp * sl + cl * east - sp * sl * north;
  const double z = n0 * (1.0 - e2) * sp + cp * north;
  const double p = std::hypot(x, y);
  double phi = std::atan2(z, p * (1.0 - e2));
  for (int i = 0; i < 8; ++i) {  // fixed point on phi; h is millimetres here
    const double s = std::sin(phi);
    const double n = a / std::sqrt(1.0 - e2 * s * s);
    const double h = p / std::cos(phi) - n;
    phi = std::atan2(z, p * (1.0 - e2 * n / (n + h)));
  }
  *lat = phi / kDegree;
  *lon = std::atan2(y, x) / kDegree;
}

bool MakeFieldLog(const Trajectory& campaign, const FieldLogOptions& options, unsigned seed,
                  Trajectory* log, std::string* error) {
  if (!options.IsValid(error)) return false;
  int column[6];
  for (int c = 0; c < 6; ++c) {
    column[c] = campaign.Find(kCampaignNames[c]);
    if (column[c] < 0) {
      *error = std::string("field log: the campaign has no column '") + kCampaignNames[c] + "'";
      return false;
    }
  }
  auto at = [&](int c, size_t row) { return campaign.columns[column[c]][row]; };
  const double step = kFieldLogCampaignStep;
  const long tick_rows = std::lround(1.0 / (options.rate * step));
  const long jitter_rows = std::lround(options.jitter / step);
  std::mt19937 random(seed);
  std::uniform_int_distribution<long> jitter(-jitter_rows, jitter_rows);

  Trajectory out;
  out.source = campaign.source + ", as a field log";
  out.names.assign(kLogNames, kLogNames + kLogColumns);
  out.columns.assign(kLogColumns, {});
  const size_t rows = campaign.t.size();
  for (size_t begin = 0; begin < rows;) {
    size_t end = begin;
    while (end < rows && at(kTrackSegment, end) == at(kTrackSegment, begin)) ++end;
    for (size_t i = begin + 1; i < end; ++i) {
      if (std::abs(campaign.t[i] - campaign.t[i - 1] - step) > 1e-6 ||
          !std::isfinite(at(kTrackNorth, i)) || !std::isfinite(at(kTrackHeading, i))) {
        *error = "field log: the campaign is not sampled every " + std::to_string(step) +
                 " s with positions and heading (t = " + std::to_string(campaign.t[i]) + ")";
        return false;
      }
    }
    const int segment = static_cast<int>(at(kTrackSegment, begin));
    size_t first = begin;  // the segment's first command: the log starts there
    while (first < end && !std::isfinite(at(kTrackPwmL, first))) ++first;
    const double length = segment == options.short_segment ? options.short_s : 1e300;
    int fixes = 0;
    double last_lat = kNaN, last_lon = kNaN;
    for (long j = 0;; ++j) {
      const long tick = static_cast<long>(first) + j * tick_rows;
      if (tick >= static_cast<long>(end) || j * tick_rows * step >= length - 1e-9) break;
      const long row = std::clamp<long>(tick + jitter(random), static_cast<long>(first),
                                        static_cast<long>(end) - 1);
      long command = row;  // the last command at or before the row
      while (!std::isfinite(at(kTrackPwmL, command))) --command;
      double value[kLogColumns];
      value[kLogSegment] = segment;
      value[kLat] = value[kLon] = kNaN;
      if (j % 2 == 0) {  // GNSS at half the logger's rate
        LocalToGeodetic(options.origin_lat, options.origin_lon, at(kTrackNorth, row),
                        at(kTrackEast, row), &value[kLat], &value[kLon]);
        if (segment == options.zero_fix_segment && fixes == kZeroFix) {
          value[kLat] = value[kLon] = 0.0;
        } else if (segment == options.stale_segment && fixes >= kStaleFrom &&
                   fixes < kStaleFrom + options.stale_fixes) {
          value[kLat] = last_lat;
          value[kLon] = last_lon;
        } else {
          last_lat = value[kLat];
          last_lon = value[kLon];
        }
        ++fixes;
      }
      double heading = std::fmod(at(kTrackHeading, row) / kDegree, 360.0);
      if (heading < 0.0) heading += 360.0;
      value[kLogHeading] = heading;
      value[kLogPwmL] = at(kTrackPwmL, command);
      value[kLogPwmR] = at(kTrackPwmR, command);
      out.t.push_back(std::round(campaign.t[row] * 1e6) / 1e6);
      for (int c = 0; c < kLogColumns; ++c) out.columns[c].push_back(value[c]);
    }
    begin = end;
  }
  *log = std::move(out);
  return true;
}

}  // namespace vesselid::input_gain
