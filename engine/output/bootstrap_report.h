// A regression stage's bootstrap (BootstrapSummary, group_bootstrap.h) as results.json,
// report.txt and report.html (report/bootstrap_html.h) show it: per parameter the estimate, bootstrap SE and percentile
// 95 % interval, per lasso coefficient the share of replicates where it is exactly zero.
#pragma once

#include <string>

#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// {"runs", "groups", "failed", "resampled", "lambda": "held" | "selected", "time_seconds",
//  "se": {name: SE}, "interval": {name: [lower, upper]}, "zero_share": {coefficient: share}}
// or {"runs": 0, "message"} when it could not run.
nlohmann::json BootstrapToJson(const BootstrapSummary& bootstrap);

// The stage's estimate of parameter `name` (NaN when it has none).
double EstimateValue(const StageResult& stage, const std::string& name);

// Lines of report.txt ("  bootstrap: ...", one per parameter and per unstable coefficient);
// empty without a bootstrap.
std::string BootstrapText(const StageResult& stage);

}  // namespace vesselid
