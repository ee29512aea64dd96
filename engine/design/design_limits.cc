#include "engine/design/design_limits.h"

#include <cmath>
#include <cstdio>

namespace vesselid {

std::vector<std::string> CheckLimits(
    const DesignOptions& options, const DesignLayout& layout, const Actuators& actuators,
    const PlannedRecord& record, const std::vector<std::pair<int, std::pair<double, double>>>& box,
    const std::vector<std::string>& outputs, double sample_time) {
  std::vector<std::string> out;
  char text[300];
  const int samples = static_cast<int>(record.time.size());
  if (samples == 0 || record.time.back() < layout.duration - 0.5 * sample_time) {
    std::snprintf(text, sizeof(text), "the record ends at %.6g s, before the %.6g s asked",
                  samples == 0 ? 0.0 : record.time.back(), layout.duration);
    out.push_back(text);
  }
  for (size_t d = 0; d < options.inputs.size(); ++d) {
    const DesignInput& in = options.inputs[d];
    const int i = layout.input[d];
    const double unit = in.degrees ? 180.0 / 3.14159265358979323846 : 1.0;
    const char* suffix = in.degrees ? " deg" : "";
    const double tolerance = 1e-9 * std::max(1.0, actuators.upper[i] - actuators.lower[i]);
    for (int k = 0; k < samples; ++k) {
      const double u = record.inputs(k, i);
      if (u < actuators.lower[i] - tolerance || u > actuators.upper[i] + tolerance) {
        std::snprintf(text, sizeof(text), "%s = %.6g%s at t = %.6g s, outside [%.6g, %.6g]",
                      in.name.c_str(), u * unit, suffix, record.time[k], actuators.lower[i] * unit,
                      actuators.upper[i] * unit);
        out.push_back(text);
        break;
      }
      if (k > 0 && actuators.rate[i] > 0.0) {
        const double rate =
            std::abs(u - record.inputs(k - 1, i)) / (record.time[k] - record.time[k - 1]);
        if (rate > actuators.rate[i] * (1.0 + 1e-9) + tolerance) {
          std::snprintf(
              text, sizeof(text), "%s changes at %.6g%s/s at t = %.6g s, beyond its rate %.6g",
              in.name.c_str(), rate * unit, suffix, record.time[k], actuators.rate[i] * unit);
          out.push_back(text);
          break;
        }
      }
    }
  }
  for (const auto& [o, range] : box) {
    for (int k = 0; k < samples; ++k) {
      const double d = record.outputs(k, o) - record.outputs(0, o);
      if (d < range.first - 1e-9 || d > range.second + 1e-9) {
        std::snprintf(text, sizeof(text),
                      "the track leaves the box: %s moves %.6g from its start at t = %.6g s, "
                      "outside [%.6g, %.6g]",
                      outputs[o].c_str(), d, record.time[k], range.first, range.second);
        out.push_back(text);
        break;
      }
    }
  }
  return out;
}

}  // namespace vesselid
