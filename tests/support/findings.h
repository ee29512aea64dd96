// Test helpers over a run's findings: every finding of a run (its own and each stage's), as
// typed objects or as results.json items, looked up by kind and by a fragment of the text.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/output/finding_report.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace testing {

// The findings of `kind` (any kind when null) whose DescribeFinding line contains `text`.
inline std::vector<Finding> FindingsOf(const RunResult& result, const FindingKind* kind,
                                       const std::string& text = "") {
  std::vector<Finding> found;
  for (const Finding& f : AllFindings(result)) {
    if (kind != nullptr && f.kind != *kind) continue;
    if (DescribeFinding(f).find(text) == std::string::npos) continue;
    found.push_back(f);
  }
  return found;
}

inline bool HasFinding(const RunResult& result, FindingKind kind, const std::string& text = "") {
  return !FindingsOf(result, &kind, text).empty();
}

// Every finding of a results.json: the run's, then each stage's.
inline std::vector<nlohmann::json> JsonFindings(const nlohmann::json& results) {
  std::vector<nlohmann::json> all;
  if (results.contains("findings")) {
    for (const nlohmann::json& f : results["findings"]) all.push_back(f);
  }
  if (results.contains("stages")) {
    for (const nlohmann::json& stage : results["stages"]) {
      if (!stage.contains("findings")) continue;
      for (const nlohmann::json& f : stage["findings"]) all.push_back(f);
    }
  }
  return all;
}

// The results.json findings of `kind` ("" for any) whose message contains `text`.
inline std::vector<nlohmann::json> JsonFindingsOf(const nlohmann::json& results,
                                                  const std::string& kind,
                                                  const std::string& text = "") {
  std::vector<nlohmann::json> found;
  for (const nlohmann::json& f : JsonFindings(results)) {
    if (!kind.empty() && f.at("kind").get<std::string>() != kind) continue;
    if (f.at("message").get<std::string>().find(text) == std::string::npos) continue;
    found.push_back(f);
  }
  return found;
}

// The first results.json finding of `kind` about `experiment`: its own, or one folded over
// several experiments that names it ("(zz1; also in zz2)"); null when there is none.
inline nlohmann::json JsonFindingFor(const nlohmann::json& results, const std::string& kind,
                                     const std::string& experiment) {
  for (const nlohmann::json& f : JsonFindingsOf(results, kind)) {
    const std::string message = f.at("message").get<std::string>();
    const size_t also = message.rfind(" (");
    if (f.at("experiment") == experiment ||
        (f.at("experiment") == "" && also != std::string::npos &&
         message.find("also in", also) != std::string::npos &&
         message.find(experiment, also) != std::string::npos)) {
      return f;
    }
  }
  return nullptr;
}

// All findings of a results.json, one DescribeFinding-like line each, for failure messages.
inline std::string JsonFindingsText(const nlohmann::json& results) {
  std::string text;
  for (const nlohmann::json& f : JsonFindings(results)) {
    text += f.at("severity").get<std::string>() + " [" + f.at("kind").get<std::string>() +
            "] stage '" + f.at("stage").get<std::string>() + "' " +
            f.at("experiment").get<std::string>() + ": " + f.at("message").get<std::string>() +
            "\n";
  }
  return text;
}

}  // namespace testing
}  // namespace vesselid
