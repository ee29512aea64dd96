#include "engine/diagnose/run_findings.h"

#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include "engine/diagnose/band_findings.h"
#include "engine/diagnose/input_noise_findings.h"
#include "engine/diagnose/record_checks.h"
#include "engine/diagnose/stage_findings.h"
#include "engine/diagnose/start_findings.h"
#include "engine/diagnose/unit_findings.h"
#include "engine/run/held_out.h"

namespace vesselid {
namespace {

// Appends final_held_out_failed findings: the final values' held-out simulation diverges, or
// predicts an output worse than holding its first measured value (pooled MAE ratio above 1).
void AddFinalHeldOutFindings(const RunResult& run, std::vector<Finding>* findings) {
  std::map<std::string, std::pair<double, double>> error_sum;  // output: (sum MAE n, hold)
  std::vector<std::string> order;
  for (const ExperimentFit& fit : run.final_validation) {
    if (fit.diverged) {
      Finding f = MakeFinding(FindingKind::kFinalHeldOutFailed, "diverges: " + fit.message);
      f.stage = "final";
      f.experiment = fit.experiment;
      findings->push_back(std::move(f));
      continue;
    }
    for (const ChannelMetrics& m : fit.channels) {
      if (error_sum.count(m.output) == 0) order.push_back(m.output);
      error_sum[m.output].first += m.mae * m.samples;
      error_sum[m.output].second += m.hold_mae * m.samples;
    }
  }
  for (const std::string& output : order) {
    const auto& sums = error_sum[output];
    if (!(sums.first > sums.second)) continue;
    char text[256];
    std::snprintf(text, sizeof(text),
                  "the simulated %s predicts the held-out data worse than holding its first "
                  "measured value (pooled MAE ratio %.3g)",
                  output.c_str(), sums.first / sums.second);
    Finding f = MakeFinding(FindingKind::kFinalHeldOutFailed, text);
    f.stage = "final";
    f.output = output;
    f.value = sums.first / sums.second;
    f.threshold = 1.0;
    findings->push_back(std::move(f));
  }
}

// A piece an equation-error stage cut from a record at a gap is named "record~k" inside the
// engine: a finding names the user's record and the piece as its segment.
void UseRecordNames(std::vector<Finding>* findings) {
  for (Finding& f : *findings) {
    const size_t cut = f.experiment.find('~');
    if (cut == std::string::npos) continue;
    if (f.segment.empty()) f.segment = f.experiment;
    f.experiment.resize(cut);
  }
}

// A finding's message without its numbers (times, counts, lengths): messages alike but for
// them give the same reason.
std::string Reason(const std::string& message) {
  std::string reason;
  for (char c : message) {
    if ((c >= '0' && c <= '9') || c == '.') continue;
    reason += c;
  }
  return reason;
}

// Findings about single pieces of records (a piece skipped, a record cut at its gaps) are one
// per kind, stage, severity and reason: the count of pieces and records and the worst case
// (the shortest piece skipped, the record cut into most pieces), not one line per piece: a
// field log's 201 skipped pieces hid the two reasons of its verdict.
void SummarisePieces(std::vector<Finding>* findings) {
  using Key = std::tuple<int, int, std::string, std::string>;
  auto key_of = [](const Finding& f) {
    return Key{static_cast<int>(f.kind), static_cast<int>(f.severity), f.stage, Reason(f.message)};
  };
  std::map<Key, std::vector<const Finding*>> groups;
  for (const Finding& f : *findings) {
    if (f.kind == FindingKind::kSegmentSkipped || f.kind == FindingKind::kRecordCut)
      groups[key_of(f)].push_back(&f);
  }
  std::vector<Finding> summaries;
  for (const auto& [key, group] : groups) {
    if (group.size() < 2) continue;
    const bool skipped = group.front()->kind == FindingKind::kSegmentSkipped;
    std::string summary_text;
    std::set<std::string> records;
    const Finding* worst = group.front();
    int pieces = 0;
    for (const Finding* f : group) {
      records.insert(f->experiment);
      pieces += skipped ? f->count : static_cast<int>(f->value);
      const bool worse = skipped ? f->value < worst->value : f->value > worst->value;
      if (worse) worst = f;
    }
    std::string names;
    int named = 0;
    for (const std::string& record : records) {
      if (++named > 6) {
        names += ", ...";
        break;
      }
      names += (names.empty() ? "" : ", ") + record;
    }
    char text[160];
    if (skipped) {
      std::snprintf(text, sizeof(text), "%d pieces of %zu record(s) skipped (", pieces,
                    records.size());
      summary_text = text + names;
      std::snprintf(text, sizeof(text), "); the shortest, %.3g s", worst->value);
    } else {
      std::snprintf(text, sizeof(text), "%zu records cut into %d pieces in all (", group.size(),
                    pieces);
      summary_text = text + names;
      std::snprintf(text, sizeof(text), "); the most");
    }
    Finding summary = *worst;
    summary.message = summary_text + text + " (" + worst->experiment +
                      (worst->segment.empty() ? "" : ", " + worst->segment) + "): " + worst->message;
    summary.count = static_cast<int>(group.size());
    if (records.size() > 1) summary.experiment.clear();
    summary.segment.clear();
    summaries.push_back(std::move(summary));
  }
  if (summaries.empty()) return;
  std::vector<Finding> kept;
  for (const Finding& f : *findings) {
    const auto group = groups.find(key_of(f));
    if (group == groups.end() || group->second.size() < 2) kept.push_back(f);
  }
  kept.insert(kept.end(), summaries.begin(), summaries.end());
  *findings = std::move(kept);
}

}  // namespace

std::vector<Finding> FoldFindings(const std::vector<Finding>& input) {
  std::vector<Finding> findings = input;
  UseRecordNames(&findings);
  SummarisePieces(&findings);
  using Key = std::tuple<int, int, std::string, std::string, std::string, std::string>;
  std::map<Key, size_t> first;
  std::vector<Finding> folded;
  std::vector<std::vector<std::string>> also;
  for (const Finding& f : findings) {
    // Record findings differ in what they say of each record (counts, times, lines): folded
    // only where the message is the same.
    static const std::set<FindingKind> kPerRecord{
        FindingKind::kSamplesRemoved, FindingKind::kBadCells,
        FindingKind::kColumnsNotRead, FindingKind::kGaps,
        FindingKind::kSegmentSkipped, FindingKind::kResampled,
        FindingKind::kRecordOrigin,   FindingKind::kRecordCut,
        FindingKind::kStaleRepeats,   FindingKind::kOutsideDataFolder};
    const bool whole_kind = !f.experiment.empty() && kPerRecord.count(f.kind) == 0;
    const Key key{static_cast<int>(f.kind), static_cast<int>(f.severity), f.stage,
                  f.parameter.substr(0, f.parameter.find('[')), f.output + "\n" + f.input,
                  whole_kind ? f.segment : f.segment + "\n" + f.message};
    const auto found = first.find(key);
    if (found == first.end()) {
      first[key] = folded.size();
      folded.push_back(f);
      also.emplace_back();
      continue;
    }
    folded[found->second].count += f.count;
    also[found->second].push_back(f.experiment);
  }
  // "(zz1; also in zz2, zz3 and 4 more)": every folded experiment stays findable by name,
  // the one whose numbers the message gives first.
  for (size_t i = 0; i < folded.size(); ++i) {
    if (also[i].empty()) continue;
    std::string names;
    for (size_t k = 0; k < also[i].size() && k < 8; ++k) names += (k > 0 ? ", " : "") + also[i][k];
    if (also[i].size() > 8) names += " and " + std::to_string(also[i].size() - 8) + " more";
    const std::string& first_name = folded[i].experiment;
    folded[i].message += " (" + (first_name.empty() ? "" : first_name + "; ") + "also in " +
                         names + ")";
    folded[i].experiment.clear();
  }
  return folded;
}

void DiagnoseRun(const RunConfig& config, RunResult* run, TrajectoryCache* records) {
  const ModelInfo& info = config.model->info();
  if (records != nullptr) {  // what the records say, first among the run's findings
    std::vector<Finding> data_findings;
    AddUnitFindings(config, records, &data_findings);
    AddRecordCheckFindings(config, records, &data_findings);
    AddInputNoiseFindings(config, *run, records, &data_findings);
    run->findings.insert(run->findings.begin(), data_findings.begin(), data_findings.end());
  }
  const DisplayUnitOf output_unit_of = OutputUnits(config);
  const ParameterUnitOf parameter_unit_of = ParameterUnits(config);
  for (StageResult& stage : run->stages) {
    const ModelHandle* model = &*config.model;
    bool output_error = true;
    for (const StageConfig& s : config.stages) {
      if (s.options.name != stage.name) continue;
      model = &config.StageModel(s);
      output_error = s.kind == StageConfig::Kind::kOutputError;
    }
    DiagnoseStage(model->info(), output_error, &stage, output_unit_of, parameter_unit_of);
    stage.findings = FoldFindings(stage.findings);
  }
  std::vector<Finding>& findings = run->findings;
  if (!run->stopped_stage.empty()) {
    Finding f = MakeFinding(FindingKind::kRunStopped,
                            "the run stopped in stage '" + run->stopped_stage + "' after " +
                                std::to_string(run->stages.size()) + " of " +
                                std::to_string(config.stages.size()) +
                                " stage(s); the results are those of the finished stages: " +
                                run->stop_message);
    f.stage = run->stopped_stage;
    findings.push_back(std::move(f));
  }
  // Every stage set aside: the final values are the config's start values, not a model.
  bool kept = false;
  for (const StageResult& stage : run->stages) kept |= stage.rejected.empty();
  for (const StageResult& stage : run->stages) {
    if (stage.rejected.empty()) continue;
    Finding f = MakeFinding(FindingKind::kStageSetAside, stage.rejected);
    f.stage = stage.name;
    if (!kept) {
      f.severity = FindingSeverity::kFailure;
      f.message += "; no stage was kept, so the final values are the config's start values, "
                   "not an estimate";
    }
    findings.push_back(std::move(f));
  }
  for (const std::string& a : run->admissibility) {
    Finding f = MakeFinding(FindingKind::kNotAdmissible, "the final values: " + a);
    f.stage = "final";
    f.severity = FindingSeverity::kFailure;
    findings.push_back(std::move(f));
  }
  for (const std::string& d : run->structure_doubts) {
    Finding f = MakeFinding(FindingKind::kUnsupportedStructure, "the final values: " + d);
    f.stage = "final";
    findings.push_back(std::move(f));
  }
  AddBoundFindings(info, run->final_held_out_parameters.estimates, "final", &findings,
                   parameter_unit_of);
  AddFinalHeldOutFindings(*run, &findings);
  AddImplausibleStartFindings(run->final_validation, "final", output_unit_of, &findings);
  AddPredictionBandFindings(*run, &findings);
  if (run->reference_check.done && run->reference_check.worse) {
    Finding f = MakeFinding(FindingKind::kWorseThanReference,
                            "the final values predict the held-out runs worse than " +
                                run->reference_check.BaselineText() + " (" +
                                DescribeReferenceCheck(*run, output_unit_of) + ")");
    f.stage = "final";
    f.value = MeanMaeRatio(run->reference_check);
    f.threshold = kHeldOutTolerance;
    findings.push_back(std::move(f));
  }
  AddFreeRunFindings(run->final_velocity_validation, "final", FindingSeverity::kFailure,
                     &findings);
  findings = FoldFindings(findings);
  SortFindings(&findings);
  Verdict verdict = VerdictOf(findings);
  for (auto stage = run->stages.rbegin(); stage != run->stages.rend(); ++stage) {
    if (!stage->rejected.empty()) continue;
    verdict = Worse(verdict, stage->verdict);
    break;
  }
  run->verdict = verdict;
}

bool Identify(const RunConfig& config, RunResult* result, std::string* error,
              const RunObserver& observer, std::vector<StageResult> finished) {
  TrajectoryCache records;
  const bool ok =
      RunIdentification(config, result, error, observer, std::move(finished), &records);
  if (ok || !result->stopped_stage.empty()) {
    DiagnoseRun(config, result, &records);
  } else {
    // A run that fails says what its records' units suggest (time in milliseconds read as
    // seconds makes the first simulation diverge).
    std::vector<Finding> units;
    AddUnitFindings(config, &records, &units);
    for (const Finding& f : units) {
      *error += "; experiment '" + f.experiment + "': " + f.message;
    }
  }
  return ok;
}

}  // namespace vesselid
