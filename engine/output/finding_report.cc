#include "engine/output/finding_report.h"

#include "engine/base/json_number.h"
#include "engine/output/report_table_cells.h"

namespace vesselid {

using nlohmann::json;

json FindingsToJson(const std::vector<Finding>& findings) {
  json list = json::array();
  for (const Finding& f : findings) {
    list.push_back({{"kind", FindingKindToString(f.kind)},
                    {"severity", FindingSeverityToString(f.severity)},
                    {"stage", f.stage},
                    {"experiment", f.experiment},
                    {"segment", f.segment},
                    {"parameter", f.parameter},
                    {"output", f.output},
                    {"value", JsonNumber(f.value)},
                    {"threshold", JsonNumber(f.threshold)},
                    {"count", f.count},
                    {"message", f.message}});
  }
  return list;
}

std::vector<Finding> AllFindings(const RunResult& result) {
  std::vector<Finding> all = result.findings;
  for (const StageResult& stage : result.stages) {
    all.insert(all.end(), stage.findings.begin(), stage.findings.end());
  }
  SortFindings(&all);
  return all;
}

namespace {

int CountOf(const std::vector<Finding>& findings, FindingSeverity severity) {
  int n = 0;
  for (const Finding& f : findings) n += f.severity == severity;
  return n;
}

const FindingSeverity kOrder[] = {FindingSeverity::kFailure, FindingSeverity::kWarning,
                                  FindingSeverity::kInfo};

const char* Heading(FindingSeverity severity) {
  switch (severity) {
    case FindingSeverity::kFailure: return "failures";
    case FindingSeverity::kWarning: return "warnings";
    case FindingSeverity::kInfo: return "notes";
  }
  return "";
}

}  // namespace

std::string VerdictLine(Verdict verdict, const std::vector<Finding>& findings) {
  return std::string("verdict: ") + VerdictToString(verdict) + " (" +
         std::to_string(CountOf(findings, FindingSeverity::kFailure)) + " failure(s), " +
         std::to_string(CountOf(findings, FindingSeverity::kWarning)) + " warning(s), " +
         std::to_string(CountOf(findings, FindingSeverity::kInfo)) + " note(s))";
}

std::string FindingsText(const std::vector<Finding>& findings, bool info,
                         const std::string& indent) {
  std::string out;
  for (FindingSeverity severity : kOrder) {
    if (severity == FindingSeverity::kInfo && !info) continue;
    const int n = CountOf(findings, severity);
    if (n == 0) continue;
    out += indent + Heading(severity) + " (" + std::to_string(n) + ")\n";
    for (const Finding& f : findings) {
      if (f.severity == severity) out += indent + "  " + DescribeFinding(f) + "\n";
    }
  }
  return out;
}

std::string FindingsHtml(const std::vector<Finding>& findings) {
  std::string out;
  for (FindingSeverity severity : kOrder) {
    const int n = CountOf(findings, severity);
    if (n == 0) continue;
    out += "<h4>" + std::string(Heading(severity)) + " (" + std::to_string(n) +
           ")</h4>\n<ul class=\"findings " + FindingSeverityToString(severity) + "\">\n";
    for (const Finding& f : findings) {
      if (f.severity != severity) continue;
      std::string where;
      if (!f.stage.empty()) where += f.stage == "final" ? "final" : "stage " + f.stage;
      if (!f.experiment.empty()) where += (where.empty() ? "" : ", ") + f.experiment;
      if (!f.parameter.empty()) where += (where.empty() ? "" : ", ") + f.parameter;
      if (!f.output.empty()) where += (where.empty() ? "" : ", ") + f.output;
      out += "<li><code>" + std::string(FindingKindToString(f.kind)) + "</code> " +
             (where.empty() ? "" : "<em>" + HtmlEscape(where) + "</em>: ") + HtmlEscape(f.message) +
             (f.count > 1 ? " (x" + std::to_string(f.count) + ")" : "") + "</li>\n";
    }
    out += "</ul>\n";
  }
  return out;
}

}  // namespace vesselid
