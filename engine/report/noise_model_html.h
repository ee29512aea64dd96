// A stage's noise model (output/noise_model_report.h) as report.html shows it.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// A heading and a small table (output, sigma, unit, samples), or empty.
std::string NoiseModelHtml(const RunConfig& config, const StageResult& stage);

}  // namespace vesselid
