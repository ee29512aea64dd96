// Findings and verdicts as the outputs show them: results.json's "findings" arrays (every
// field of Finding), report.txt's and report.html's (report/finding_html.h) lists grouped by severity then kind,
// and stderr's lines.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json FindingsToJson(const std::vector<Finding>& findings);

// Every finding of the run: its own, then each stage's, in output order (severity first).
std::vector<Finding> AllFindings(const RunResult& result);

// Severities in the order the outputs list them, worst first, and the heading of each
// ("failures", "warnings", "notes"); the findings of one severity.
inline constexpr FindingSeverity kSeverityOrder[] = {
    FindingSeverity::kFailure, FindingSeverity::kWarning, FindingSeverity::kInfo};
const char* SeverityHeading(FindingSeverity severity);
int CountOf(const std::vector<Finding>& findings, FindingSeverity severity);

// "verdict: doubtful (0 failure(s), 3 warning(s), 2 note(s))".
std::string VerdictLine(Verdict verdict, const std::vector<Finding>& findings);

// Plain-text lists, one line per finding under a heading per severity ("failures (1)");
// `info`: include the info findings.
std::string FindingsText(const std::vector<Finding>& findings, bool info,
                         const std::string& indent = "  ");

}  // namespace vesselid
