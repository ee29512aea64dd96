// A finding: one typed statement about a run, a stage, a record or a parameter, with the
// value it measured and the threshold of its rule, e.g.
//   {kind: at_bound, severity: warning, stage: "yaw", parameter: "N_r", value: 0, threshold: 0}.
// Every judgement the engine makes is a Finding; outputs render them, nothing classifies
// text. The catalogue (FindingCatalogue) states each kind's rule, threshold and advice in one
// place; the docs' list of kinds is generated from it (`vesselid findings`).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vesselid {

// info: context a careful reader wants; warning: doubt about the result that a user should
// look at; failure: the result (or part of it) is not to be used as it is.
enum class FindingSeverity { kInfo, kWarning, kFailure };

const char* FindingSeverityToString(FindingSeverity severity);  // "info", "warning", "failure"
bool StringToFindingSeverity(const std::string& text, FindingSeverity* severity);

enum class FindingKind {
  // Run.
  kRunStopped,
  // Records as read.
  kSamplesRemoved,
  kBadCells,
  kColumnsNotRead,
  kGaps,
  kResampled,
  kRecordOrigin,
  kOutsideDataFolder,
  kSegmentSkipped,
  kRecordCut,
  kUnitSuspect,
  kQuantised,
  kStaleRepeats,
  kAllZeroInput,
  kStartsMidManoeuvre,
  kCheckSkipped,
  // Solver.
  kAtBound,
  kWeaklyDetermined,
  kNoConvergence,
  kNoProgress,
  kIntegrationStep,
  kOutliers,
  kNoiseModel,
  kDisturbanceModel,
  kDisturbanceAbsorbsStructure,
  kFreeRunDrift,
  kGlobalStartDiverged,
  kNarrowIntervals,
  kBootstrap,
  kCompensation,
  kInputNoise,
  // Fit and residuals.
  kFailedFit,
  kPoorFit,
  kColouredResiduals,
  kInputCorrelatedResiduals,
  kNotAdmissible,
  kUnsupportedStructure,
  // Held-out data.
  kStageSetAside,
  kHeldOutWorse,
  kHeldOutOutputWorse,
  kHeldOutDiverged,
  kHeldOutFreeRunFailed,
  kFinalHeldOutFailed,
  kImplausibleStart,
  kHeldOutBeyondBand,
  kWorseThanReference,
};

const char* FindingKindToString(FindingKind kind);  // snake_case, e.g. "at_bound"
bool StringToFindingKind(const std::string& text, FindingKind* kind);

struct Finding {
  FindingKind kind = FindingKind::kRunStopped;
  FindingSeverity severity = FindingSeverity::kWarning;
  std::string stage;       // "" at run level or for a record; "final" for the final values
  std::string experiment;  // the user's experiment name, "" when not one
  std::string segment;     // e.g. "120-240 s" of a record's piece, "" when the whole record
  std::string parameter;   // model parameter (or "a, b" for a group), "" when none
  std::string output;      // model output, "" when none
  std::string input;       // model input (a rudder column), "" when none
  double value = std::numeric_limits<double>::quiet_NaN();      // what the rule measured
  double threshold = std::numeric_limits<double>::quiet_NaN();  // where the rule fires
  int count = 1;  // repeats folded into this one (e.g. segments with coloured residuals)
  std::string message;  // one sentence for a person, in the data's units
};

// Builds a finding of `kind` with its catalogue severity.
Finding MakeFinding(FindingKind kind, std::string message);

// Appends `finding` unless an identical one (kind, experiment, segment, message) is there.
void AddFindingOnce(Finding finding, std::vector<Finding>* findings);

// The kind's entry in the catalogue.
struct FindingRule {
  FindingKind kind;
  FindingSeverity severity;  // default; some rules raise it (stated in `rule`)
  const char* rule;          // what triggers it, with the threshold and why
  const char* advice;        // what to do
};
const std::vector<FindingRule>& FindingCatalogue();
const FindingRule& RuleOf(FindingKind kind);

// The catalogue as a Markdown table (docs/findings.md is this text).
std::string FindingCatalogueMarkdown();

// Verdict of a set of findings: good (nothing above info), doubtful (a warning), failed (a
// failure).
enum class Verdict { kGood, kDoubtful, kFailed };
const char* VerdictToString(Verdict verdict);  // "good", "doubtful", "failed"
bool StringToVerdict(const std::string& text, Verdict* verdict);
Verdict VerdictOf(const std::vector<Finding>& findings);
Verdict Worse(Verdict a, Verdict b);

// "failure [failed_fit] stage 'yaw', experiment 'zz1', output psi: message (x3)".
std::string DescribeFinding(const Finding& finding);

// Orders findings severity first (failure, warning, info), then by kind, stage, experiment.
void SortFindings(std::vector<Finding>* findings);

}  // namespace vesselid
