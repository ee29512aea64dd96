#include "engine/output/finding_report.h"

#include "engine/base/json_number.h"

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
                    {"input", f.input},
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

int CountOf(const std::vector<Finding>& findings, FindingSeverity severity) {
  int n = 0;
  for (const Finding& f : findings) n += f.severity == severity;
  return n;
}

const char* SeverityHeading(FindingSeverity severity) {
  switch (severity) {
    case FindingSeverity::kFailure: return "failures";
    case FindingSeverity::kWarning: return "warnings";
    case FindingSeverity::kInfo: return "notes";
  }
  return "";
}

std::string VerdictLine(Verdict verdict, const std::vector<Finding>& findings) {
  return std::string("verdict: ") + VerdictToString(verdict) + " (" +
         std::to_string(CountOf(findings, FindingSeverity::kFailure)) + " failure(s), " +
         std::to_string(CountOf(findings, FindingSeverity::kWarning)) + " warning(s), " +
         std::to_string(CountOf(findings, FindingSeverity::kInfo)) + " note(s))";
}

std::string FindingsText(const std::vector<Finding>& findings, bool info,
                         const std::string& indent) {
  std::string out;
  for (FindingSeverity severity : kSeverityOrder) {
    if (severity == FindingSeverity::kInfo && !info) continue;
    const int n = CountOf(findings, severity);
    if (n == 0) continue;
    out += indent + SeverityHeading(severity) + " (" + std::to_string(n) + ")\n";
    for (const Finding& f : findings) {
      if (f.severity == severity) out += indent + "  " + DescribeFinding(f) + "\n";
    }
  }
  return out;
}

}  // namespace vesselid
