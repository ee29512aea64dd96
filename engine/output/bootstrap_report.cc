#include "engine/output/bootstrap_report.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/json_number.h"
#include "engine/output/report_table_cells.h"

namespace vesselid {
namespace {

double EstimateValue(const StageResult& stage, const std::string& name) {
  for (const Estimate& e : stage.estimates) {
    if (e.name == name) return e.value;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string Format(const char* format, double value) {
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

}  // namespace

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

std::string BootstrapHtml(const StageResult& stage) {
  const BootstrapSummary& b = stage.bootstrap;
  if (!b.done()) {
    return b.message.empty() ? "" : "<p>Bootstrap not run: " + HtmlEscape(b.message) + "</p>\n";
  }
  std::string html = "<h4>Bootstrap</h4>\n<p>" + HtmlEscape(BootstrapDescription(b)) +
                     ": standard error = SD of the replicates, 95 % percentile interval.</p>\n";
  std::string rows;
  for (size_t k = 0; k < b.names.size(); ++k) {
    const bool zero = b.lower[k] <= 0.0 && b.upper[k] >= 0.0;
    rows += "<tr>" + Td(b.names[k]) + Num(Format("%.6g", EstimateValue(stage, b.names[k]))) +
            Num(Format("%.3g", b.std_error[k])) + Num(Format("%.6g", b.lower[k])) +
            Num(Format("%.6g", b.upper[k])) + Td(zero ? "contains 0" : "") + "</tr>\n";
  }
  html += Fold("<table>\n<tr>" + Th("parameter") + Th("estimate") + Th("bootstrap SE") +
                   Th("2.5 %") + Th("97.5 %") + Th("") + "</tr>\n" + rows + "</table>\n",
               b.names.size(), "bootstrap intervals of " + std::to_string(b.names.size()) +
                                   " parameters", 24);
  if (!b.coefficient_names.empty()) {
    rows.clear();
    for (size_t k = 0; k < b.coefficient_names.size(); ++k) {
      rows += "<tr>" + Td(b.coefficient_names[k]) +
              Num(Format("%.1f", 100.0 * b.zero_share[k])) +
              Td(UnstableSelection(b.zero_share[k]) ? "unstable" : "") + "</tr>\n";
    }
    html += Fold("<table>\n<tr>" + Th("lasso coefficient") + Th("zero in % of replicates") +
                     Th("") + "</tr>\n" + rows + "</table>\n",
                 b.coefficient_names.size(), "lasso selection stability", 24);
  }
  return html;
}

}  // namespace vesselid
