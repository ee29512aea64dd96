#include "engine/diagnose/bootstrap_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

void AddBootstrapFindings(const StageResult& stage, std::vector<Finding>* findings) {
  const auto add = [&](std::string message, std::string parameter = "") {
    Finding f = MakeFinding(FindingKind::kBootstrap, std::move(message));
    f.stage = stage.name;
    f.parameter = std::move(parameter);
    findings->push_back(std::move(f));
  };
  const BootstrapSummary& b = stage.bootstrap;
  if (!b.done()) {
    if (!b.message.empty()) add("the bootstrap did not run: " + b.message);
    return;
  }
  if (b.failed > b.runs / 10) {
    add(std::to_string(b.failed) + " of " + std::to_string(b.runs) +
                        " bootstrap replicates could not be fitted (too few distinct groups "
                        "drawn, or a failed fit): the bootstrap SEs rest on the rest");
  }
  // An estimate within rounding of zero (a coefficient the lasso dropped, expanded into the
  // model's basis) is zero, not a doubtful estimate.
  std::vector<double> values(b.names.size(), 0.0);
  double largest = 0.0;
  for (size_t k = 0; k < b.names.size(); ++k) {
    for (const Estimate& e : stage.estimates) {
      if (e.name == b.names[k]) values[k] = e.value;
    }
    largest = std::max(largest, std::abs(values[k]));
  }
  std::string zero;
  for (size_t k = 0; k < b.names.size(); ++k) {
    if (std::abs(values[k]) > 1e-12 * largest && b.lower[k] <= 0.0 && b.upper[k] >= 0.0) {
      zero += " " + b.names[k] + ",";
    }
  }
  if (!zero.empty()) {
    zero.pop_back();
    add("the 95 % bootstrap interval contains 0 for" + zero +
            ": not distinguishable from zero on these data",
        zero.substr(1));
  }
  std::string unstable;
  char text[128];
  for (size_t k = 0; k < b.coefficient_names.size(); ++k) {
    if (!UnstableSelection(b.zero_share[k])) continue;
    std::snprintf(text, sizeof(text), " %s (%.0f %%),", b.coefficient_names[k].c_str(),
                  100.0 * b.zero_share[k]);
    unstable += text;
  }
  if (!unstable.empty()) {
    unstable.pop_back();
    add("unstable lasso selection, zero in 20-80 % of the bootstrap replicates:" + unstable);
  }
}

}  // namespace vesselid
