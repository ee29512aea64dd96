#include "engine/output/bootstrap_report.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/json_number.h"

namespace vesselid {
double EstimateValue(const StageResult& stage, const std::string& name) {
  for (const Estimate& e : stage.estimates) {
    if (e.name == name) return e.value;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json BootstrapToJson(const BootstrapSummary& b) {
  if (!b.done()) return {{"runs", 0}, {"message", b.message}};
  nlohmann::json se = nlohmann::json::object(), interval = nlohmann::json::object(),
                 zero = nlohmann::json::object();
  for (size_t k = 0; k < b.names.size(); ++k) {
    se[b.names[k]] = JsonNumber(b.std_error[k]);
    interval[b.names[k]] = {JsonNumber(b.lower[k]), JsonNumber(b.upper[k])};
  }
  for (size_t k = 0; k < b.coefficient_names.size(); ++k) {
    zero[b.coefficient_names[k]] = JsonNumber(b.zero_share[k]);
  }
  return {{"runs", b.runs},
          {"groups", b.groups},
          {"failed", b.failed},
          {"resampled", b.resampled},
          {"lambda", b.lambda_held ? "held" : "selected"},
          {"time_seconds", b.time_seconds},
          {"se", se},
          {"interval", interval},
          {"zero_share", zero}};
}

std::string BootstrapText(const StageResult& stage) {
  const BootstrapSummary& b = stage.bootstrap;
  if (!b.done()) {
    return b.message.empty() ? "" : "  bootstrap: not run: " + b.message + "\n";
  }
  std::string out = "  " + BootstrapDescription(b) + ":\n";
  char line[256];
  for (size_t k = 0; k < b.names.size(); ++k) {
    std::snprintf(line, sizeof(line), "    %-16s %12.6g  SE %-10.3g 95 %% [%.6g, %.6g]%s\n",
                  b.names[k].c_str(), EstimateValue(stage, b.names[k]), b.std_error[k],
                  b.lower[k], b.upper[k], b.lower[k] <= 0.0 && b.upper[k] >= 0.0 ? "  (0 inside)" : "");
    out += line;
  }
  std::string unstable;
  for (size_t k = 0; k < b.coefficient_names.size(); ++k) {
    if (!UnstableSelection(b.zero_share[k])) continue;
    std::snprintf(line, sizeof(line), " %s %.0f %%;", b.coefficient_names[k].c_str(),
                  100.0 * b.zero_share[k]);
    unstable += line;
  }
  if (!b.coefficient_names.empty()) {
    out += "    lasso selection, share of replicates with the coefficient zero (20-80 %: "
           "unstable):" + (unstable.empty() ? std::string(" none unstable") : unstable) + "\n";
  }
  return out;
}

}  // namespace vesselid
