#include "engine/output/noise_model_report.h"

#include <cstdio>
#include <sstream>

#include "engine/base/json_number.h"
#include "engine/run/display_units.h"

namespace vesselid {
// The unit of output `output` as the stage's first experiment comparing it reads it.
DisplayUnit NoiseUnitOf(const RunConfig& config, const StageResult& stage, const std::string& output) {
  for (const ExperimentFit& fit : stage.summary.fits) {
    for (const ChannelMetrics& m : fit.channels) {
      if (m.output == output) return OutputDisplayUnit(config, fit.experiment, output);
    }
  }
  return OutputDisplayUnit(config, "", output);
}

std::string NoiseSettling(const NoiseModel& noise) {
  return std::to_string(noise.iterations) + " re-solve" + (noise.iterations == 1 ? "" : "s") +
         (noise.converged ? ", settled" : ", did not settle");
}

nlohmann::json NoiseModelToJson(const RunConfig& config, const StageResult& stage) {
  const NoiseModel& noise = stage.noise_model;
  if (!noise.active()) return nullptr;
  nlohmann::json sigma = nlohmann::json::object(), units = nlohmann::json::object(),
                 samples = nlohmann::json::object();
  for (size_t k = 0; k < noise.outputs.size(); ++k) {
    const DisplayUnit unit = NoiseUnitOf(config, stage, noise.outputs[k]);
    sigma[noise.outputs[k]] = JsonNumber(noise.sigma[k] * unit.scale);
    units[noise.outputs[k]] = unit.unit;
    samples[noise.outputs[k]] = noise.samples[k];
  }
  return {{"method", noise.method}, {"iterations", noise.iterations},
          {"converged", noise.converged}, {"sigma", sigma}, {"units", units},
          {"samples", samples}};
}

std::string NoiseModelText(const RunConfig& config, const StageResult& stage) {
  const NoiseModel& noise = stage.noise_model;
  if (!noise.active()) return "";
  std::string text = "  noise model: sigma";
  for (size_t k = 0; k < noise.outputs.size(); ++k) {
    const DisplayUnit unit = NoiseUnitOf(config, stage, noise.outputs[k]);
    char item[160];
    std::snprintf(item, sizeof(item), "%s %s %.4g%s%s", k == 0 ? "" : ",",
                  noise.outputs[k].c_str(), noise.sigma[k] * unit.scale,
                  unit.unit.empty() ? "" : " ", unit.unit.c_str());
    text += item;
  }
  return text + " (weights 1/sigma; " + NoiseSettling(noise) + ")\n";
}

}  // namespace vesselid
