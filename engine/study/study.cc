#include "engine/study/study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "engine/base/memory_budget.h"
#include "engine/study/monte_carlo_study.h"
#include "engine/study/partition_study.h"
#include "engine/study/profile_likelihood.h"
#include "engine/study/start_point_study.h"
#include "engine/study/study_json.h"
#include "engine/study/study_runner.h"

namespace vesselid {

using nlohmann::json;

const std::vector<std::string>& StudyPartNames() {
  static const std::vector<std::string> names = {"profile", "monte_carlo", "starts",
                                                 "partitions"};
  return names;
}

bool RunStudy(const RunConfig& config, const StudyConfig& study,
              const std::vector<std::string>& only, json* result,
              std::string* text, std::string* error,
              const std::function<void(const std::string&)>& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  const ScopedMemoryBudget budget(config.limits.memory_bytes);
  auto configured = [&](const std::string& part) {
    if (part == "profile") return study.profile.has_value();
    if (part == "monte_carlo") return study.monte_carlo.has_value();
    if (part == "starts") return study.starts.has_value();
    return study.partitions.has_value();
  };
  for (const std::string& part : only) {
    if (std::find(StudyPartNames().begin(), StudyPartNames().end(), part) ==
        StudyPartNames().end()) {
      *error = "unknown study part '" + part + "' (profile, monte_carlo, starts, partitions)";
      return false;
    }
    if (!configured(part)) {
      *error = config.path + ": study." + part + " is not configured";
      return false;
    }
  }
  std::vector<std::string> parts;
  for (const std::string& part : StudyPartNames()) {
    const bool wanted = only.empty() || std::find(only.begin(), only.end(), part) != only.end();
    if (wanted && configured(part)) parts.push_back(part);
  }
  if (parts.empty()) {
    *error = config.path + ": the config's study section names no part (" +
             "profile, monte_carlo, starts, partitions)";
    return false;
  }
  const ProcessGroup& group = ProcessGroup::Current();
  json merged = {{"config", config.path},
                 {"seed", study.seed},
                 {"processes", group.size()},
                 {"threads_per_process", CaseThreads(study.execution)}};
  std::string report;
  for (const std::string& part : parts) {
    int done = 0;
    CaseProgress case_progress = [&](int index, const json& c) {
      ++done;
      if (progress) {
        char line[160];
        std::snprintf(line, sizeof(line), "%s: case %d done%s (%d on this process)",
                      part.c_str(), index, c.value("usable", true) ? "" : " (unusable)", done);
        progress(line);
      }
    };
    json section;
    bool ok = true;
    if (part == "profile") {
      ok = RunProfileLikelihood(config, *study.profile, study.execution, &section, error,
                                case_progress);
      if (ok && group.root()) report += ProfileText(section);
    } else if (part == "monte_carlo") {
      ok = RunMonteCarloStudy(config, *study.monte_carlo, study.seed, study.execution, &section,
                              error, case_progress);
      if (ok && group.root()) report += MonteCarloText(section);
    } else if (part == "starts") {
      ok = RunStartPointStudy(config, *study.starts, study.seed, study.execution, &section,
                              error, case_progress);
      if (ok && group.root()) report += StartPointText(section);
    } else {
      StudyOptions options = *study.partitions;
      options.seed = study.seed;
      StudyResult partitions;
      ok = RunPartitionStudy(config, options, study.execution, &partitions, error,
                             case_progress);
      if (ok && group.root()) {
        section = StudyResultToJson(partitions);
        report += StudyResultToText(partitions);
      }
    }
    if (!ok) {
      *error = "study " + part + ": " + *error;
      return false;
    }
    if (group.root()) {
      merged[part] = std::move(section);
      report += "\n";
    }
  }
  if (!group.root()) {
    *result = nullptr;
    text->clear();
    return true;
  }
  merged["time_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(merged);
  *text = report;
  return true;
}

bool RunStudy(const RunConfig& config, const StudyConfig& study,
              const std::vector<std::string>& only, std::string* json_text, std::string* text,
              std::string* error, const std::function<void(const std::string&)>& progress) {
  json result;
  if (!RunStudy(config, study, only, &result, text, error, progress)) return false;
  *json_text = result.is_null() ? std::string() : result.dump(2);
  return true;
}

}  // namespace vesselid
