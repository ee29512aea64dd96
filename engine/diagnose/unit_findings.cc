#include "engine/diagnose/unit_findings.h"

#include <algorithm>
#include <cmath>

#include "engine/data/angle_units.h"

namespace vesselid {

void AddUnitFindings(const RunConfig& config, TrajectoryCache* cache,
                     std::vector<Finding>* findings) {
  const ModelInfo& info = config.model->info();
  for (const ExperimentSpec& spec : config.experiments) {
    for (const auto& [output, column] : spec.outputs) {
      const int o = info.OutputIndex(output);
      if (o < 0 || o >= static_cast<int>(info.angle_outputs.size()) || !info.angle_outputs[o]) {
        continue;
      }
      const std::vector<std::string>& degrees = spec.degree_columns;
      if (std::find(degrees.begin(), degrees.end(), column) != degrees.end()) continue;
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values)) continue;
      const AngleUnitCheck check = CheckAngleUnit(values);
      if (check.looks_like_degrees) {
        Finding f = MakeFinding(FindingKind::kUnitSuspect, DescribeDegreesLook(column, check));
        f.experiment = spec.name;
        f.output = output;
        findings->push_back(std::move(f));
      }
    }
  }
}

}  // namespace vesselid
