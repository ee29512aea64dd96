#include "engine/output/stage_interpolation.h"

#include "engine/data/interpolation.h"

namespace vesselid {

std::map<std::string, std::string> StageInterpolation(const RunConfig& config,
                                                      const StageConfig& stage) {
  std::map<std::string, std::string> methods;
  for (const std::string& input : config.model->info().inputs) {
    std::map<std::string, int> count;
    for (const std::string& name : stage.experiments) {
      for (const ExperimentSpec& spec : config.experiments) {
        if (spec.name != name) continue;
        const auto method = spec.interpolation.find(input);
        ++count[InterpolationToString(
            method == spec.interpolation.end() ? spec.default_interpolation : method->second)];
      }
    }
    std::string most = InterpolationToString(Interpolation::kLinear);
    int most_count = 0;
    for (const auto& [method, n] : count) {
      if (n > most_count) most = method, most_count = n;
    }
    methods[input] = most;
  }
  return methods;
}

}  // namespace vesselid
