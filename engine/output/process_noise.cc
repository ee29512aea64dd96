#include "engine/output/process_noise.h"

namespace vesselid {

namespace {
// engine/model/disturbance.cc names a state's process noise so.
constexpr char kPrefix[] = "q.process.";
}  // namespace

bool ProcessNoiseNamed(const std::string& name, double value, double std_error,
                       ProcessNoise* noise) {
  const std::string prefix = kPrefix;
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size()) return false;
  noise->state = name.substr(prefix.size());
  noise->spectral_density = value;
  noise->std_error = std_error;
  return true;
}

std::vector<ProcessNoise> ProcessNoiseOf(const std::vector<Estimate>& estimates) {
  std::vector<ProcessNoise> found;
  for (const Estimate& e : estimates) {
    ProcessNoise noise;
    if (e.kind == EstimateKind::kNoise && ProcessNoiseNamed(e.name, e.value, e.std_error, &noise)) {
      found.push_back(noise);
    }
  }
  return found;
}

}  // namespace vesselid
