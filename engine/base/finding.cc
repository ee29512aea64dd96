#include "engine/base/finding.h"

#include <algorithm>
#include <tuple>

namespace vesselid {
namespace {

using K = FindingKind;
using S = FindingSeverity;

// One row per kind, in enum order: name, severity, rule, advice.
struct Row {
  K kind;
  const char* name;
  S severity;
  const char* rule;
  const char* advice;
};

const Row kRows[] = {
    {K::kRunStopped, "run_stopped", S::kFailure,
     "The run stopped before its last stage (a stage could not be solved); the results are "
     "those of the finished stages.",
     "Read the message: it names the stage and the cause."},
    {K::kSamplesRemoved, "samples_removed", S::kWarning,
     "The screen (`screen:`) or a position fix of exactly 0/0 removed samples of a measured "
     "output; the finding gives the count per kind and channel and the first times.",
     "Check the times it names; loosen `screen:` if real motion was removed."},
    {K::kBadCells, "bad_cells", S::kWarning,
     "Cells of a mapped column held text that is not a number (a spreadsheet's mangled cell "
     "such as `jan.68`, `NaN`, `inf`): each is read as a missing sample. Above the experiment's "
     "`bad_cells` share (default 5 % of the column's rows) the file is refused instead. Columns "
     "no experiment maps are not read at all.",
     "Check the first lines the finding names; fix the logger or export, or accept the gaps."},
    {K::kColumnsNotRead, "columns_not_read", S::kInfo,
     "A record's file has columns the experiment does not map (unnamed ones too, such as a "
     "spreadsheet's index): they are skipped unread, so text in them is no error.",
     "None; check the list if a mapping was mistyped."},
    {K::kGaps, "gaps", S::kInfo,
     "A mapped output has gaps longer than 3 of its median sample intervals (a logger that "
     "stopped, rows removed). Output error simulates across them; an equation-error stage cuts "
     "the record there (record_cut).",
     "None; a long gap in a manoeuvre costs its information."},
    {K::kResampled, "resampled", S::kInfo,
     "A record was resampled to a uniform grid (`resample:`).",
     "None; the grid serves every stage."},
    {K::kRecordOrigin, "record_origin", S::kInfo,
     "Times were Unix epoch seconds (t = 0 is the first time), or positions were GNSS fixes "
     "mapped to north/east metres about an origin.",
     "None; results.json's `record_origins` gives the origin."},
    {K::kOutsideDataFolder, "outside_data_folder", S::kInfo,
     "A data file lies outside the data folder (--data, else the config's folder): an "
     "absolute `file:`, a `../` path or a pattern that leaves the folder, read because the "
     "config allows it (`limits: {outside_data: true}`).",
     "None if the file is the one meant; else give --data the folder that holds the data."},
    {K::kSegmentSkipped, "segment_skipped", S::kWarning,
     "A piece of a record has fewer samples than a stage needs (a least-squares stage: its "
     "Savitzky-Golay window; an output-error stage: the model's number of states) and is left "
     "out of that stage. Two or more are one finding: the count of pieces and records and the "
     "shortest piece.",
     "Lengthen the piece, shorten the smoothing window, or accept the loss."},
    {K::kRecordCut, "record_cut", S::kInfo,
     "An equation-error stage cut a record into pieces at gaps of its grid output: steps "
     "longer than the stage's max_gap and at least 2 median steps (a missing sample). The same "
     "rule decides where a piece is built, so a record, resampled or not, is cut or accepted; "
     "only row jitter beyond max_gap is refused. Two or more records cut are one finding: the "
     "count of records and pieces and the record cut into most.",
     "None; raise `least_squares: {max_gap: ...}` to bridge the gaps."},
    {K::kUnitSuspect, "unit_suspect", S::kWarning,
     "An angle output not listed under `degrees:` looks like degrees: it swings back and forth "
     "over more than one turn (a heading that turns steadily, a spiral, is not counted), or "
     "steps by more than pi within one turn; an angle input (a rudder) not listed goes beyond "
     "90 deg, which no rudder or fin does; or a record's median sample interval is above 10 s "
     "(milliseconds read as seconds) or below 1 ms (seconds read as milliseconds).",
     "Add the column to the experiment's `degrees:` if it was logged in degrees; give the time "
     "column's unit (`time: {unit: ms}`) if it is not seconds."},
    {K::kQuantised, "quantised", S::kInfo,
     "A mapped channel's distinct values lie on a grid (95 % of the gaps between neighbouring "
     "values are whole steps, fewer distinct values than a fifth of the samples): a compass in "
     "whole degrees, a rudder indicator in 1-degree steps. Its noise is at least step / "
     "sqrt(12).",
     "None needed for output error; expect coloured residuals of about that size."},
    {K::kStaleRepeats, "stale_repeats", S::kInfo,
     "A measured output (not quantised) repeats its value exactly in runs of 3 or more samples "
     "while a mapped input or another output changes, in at least 1 % of its samples: a sensor "
     "or logger that held its last value. The held samples pull the fit towards a delay.",
     "Remove them with the experiment's `screen: {stale: 3}`."},
    {K::kAllZeroInput, "all_zero_input", S::kWarning,
     "A mapped input column is exactly 0 in every sample of the window: the parameters it drives "
     "cannot be identified from this record.",
     "Check the column mapping and the logger."},
    {K::kStartsMidManoeuvre, "starts_mid_manoeuvre", S::kInfo,
     "An angle input (a rudder) starts at 40 % or more of its largest magnitude in the record: "
     "the record starts mid-manoeuvre and its initial states carry the past.",
     "Free the initial states (`free_initial_states`) or cut the record where it is at rest."},
    {K::kCheckSkipped, "check_skipped", S::kWarning,
     "An optional check could not be made (the velocity validation of held-out records with "
     "gaps its equation-error grid refuses): it is left out and the run goes on.",
     "The finding names the key that turns the check off (velocity_validation: false)."},
    {K::kAtBound, "at_bound", S::kWarning,
     "A free estimate, as reported, lies within 1e-6 of its range from a bound: the data pull "
     "it further, and its standard error assumes an interior optimum. Computed from the "
     "reported value, so it is never stale after a re-solve.",
     "Widen the bound if the physics allow it, or fix the parameter; a bound the physics "
     "require means the structure is wrong."},
    {K::kWeaklyDetermined, "weakly_determined", S::kWarning,
     "A free shared estimate off its bounds whose standard error is above 50 % of its value "
     "(of 1 % of its bound range, for a value near 0), or that the stage's covariance calls "
     "undetermined (a note where only its sign is unknown: its 95 % interval spans 0 while "
     "the error is small beside the bound range): the data say little about it, and its value is a consequence of the start "
     "and the others. One finding per stage lists them.",
     "Hold it at a known value, or add records that excite it (a richer input, a longer run)."},
    {K::kNoConvergence, "no_convergence", S::kWarning,
     "The solver stopped at its iteration limit (`local.max_iterations`) without meeting a "
     "tolerance: the estimate may not be an optimum.",
     "Raise `local.max_iterations`, or start closer (a least-squares stage)."},
    {K::kNoProgress, "no_progress", S::kWarning,
     "The chosen solve ended where it started: 0 successful steps, or the cost fell by less "
     "than 1e-9 of itself with free parameters. A solver stuck at its start reports "
     "convergence without having searched.",
     "Check the scales (`scale:`) and the start; a start on a flat region needs a global "
     "start."},
    {K::kIntegrationStep, "integration_step", S::kWarning,
     "The configured integration step was too long for the estimate's dynamics (RK4's "
     "stability limit): the stage was solved again with a shorter step, or could not be.",
     "Set `integration: {max_step: ...}` to the step the finding names."},
    {K::kOutliers, "outliers", S::kWarning,
     "Experiments whose RMS cost is far above the rest (above median + 5 x 1.4826 MAD of the "
     "costs and above twice the median; with `outliers: {threshold: k}`, k x MAD and "
     "(1 + k/5) x the median), or free initial states that end far from the data's "
     "guess (OutlierOptions).",
     "Look at the named records; drop them (`outliers: drop`) if they are broken."},
    {K::kNoiseModel, "noise_model", S::kWarning,
     "Under `weights: noise` the per-channel noise model did not settle, or could not be "
     "estimated (the configured weights stay).",
     "Give `weights:` per output."},
    {K::kDisturbanceModel, "disturbance_model", S::kInfo,
     "The filter-error method (`noise:`) identified the disturbance with the ship: what the "
     "model does not explain, named as the noise it is (a sensor's AR(1) noise with its time "
     "constant and SD, wave yaw with its peak frequency, process noise on a state's equation, a "
     "drifting bias), judged on the filter's innovations: white innovations say the colour of "
     "output error's residuals was noise; coloured ones (coloured_residuals on the "
     "innovations) say structure remains.",
     "None: read the estimates beside the ship's. A process noise far above what the sea and "
     "sensors can make stands for structure the model lacks."},
    {K::kDisturbanceAbsorbsStructure, "disturbance_absorbs_structure", S::kWarning,
     "A disturbance model absorbs structure the ship model lacks (a rudder dead band or rate "
     "limit, a missing nonlinear term): process noise does what the model cannot and the "
     "innovations come out white in time. They still follow functions of what was known before "
     "their sample, which under a correct model they cannot, whatever the noise: the filter's "
     "normalised innovations are regressed on s, s|s| and s^3 of the output's predicted rate "
     "and of each input, and N R^2 against chi^2 falls below p = 0.001 over the stage's tests "
     "(the independent corpus's sensor, wave, gust and drift classes: N R^2 at most 11.1 of 6; "
     "its dead band, rate limit and cubic damping classes up to 119). Or, where process noise "
     "acts on a state, the likelihood's score test through the filter of terms added to that "
     "state's equation (a constant, sign(z), z, z|z|, z^3 of each velocity and input) falls "
     "below the same level: the likelihood asks for a term the model lacks.",
     "Look for the missing structure (vesselid select over richer families); the estimates "
     "of neither method are to be trusted as they are."},
    {K::kFreeRunDrift, "free_run_drift", S::kInfo,
     "In place of a filter-error stage's failed_fit or poor_fit: the free run (the model flown "
     "alone from the record's start with the logged inputs) misses its record by no more than "
     "the process noise identified with the ship lets a correct model drift (its residuals' "
     "sum of squares at most 8 times the expected one, the spread of 64 free runs each in its "
     "own realisation of the identified gusts plus the sensors' variance), and neither the "
     "filter's innovations nor the score test of terms the model may lack "
     "(disturbance_absorbs_structure) show structure. A correct model in strong gusts drifts "
     "so; where structure is missing but the data cannot show it, so does a wrong one (the "
     "gust corpus, docs/models.md).",
     "Judge the model by its one-step and k-step predictions through the filter, the "
     "intervals with disturbance of vesselid predict, and records with milder gusts, where a "
     "correct model's free run holds."},
    {K::kGlobalStartDiverged, "global_start_diverged", S::kInfo,
     "Points of the global search whose simulation diverged were left out.",
     "None unless most diverged: then narrow the bounds."},
    {K::kNarrowIntervals, "narrow_intervals", S::kWarning,
     "The reported standard errors are known to be too narrow: coloured residuals under the "
     "Hessian's covariance (by the HAC's ratio), or latent input splines held exact.",
     "Use `uncertainty: {method: sandwich_hac}` or a bootstrap."},
    {K::kBootstrap, "bootstrap", S::kWarning,
     "The bootstrap could not run, lost replicates, or found an interval containing 0 or an "
     "unstable lasso selection.",
     "Read the message; more runs or blocks may help."},
    {K::kCompensation, "compensation", S::kWarning,
     "Two estimates of a stage correlate beyond 0.999 (per-experiment values included) while "
     "either has a relative standard error of 30 % or more (pairs determined to 8-20 % at "
     "correlation 0.999 fit well in the verdict corpus; the USV log's b_u and k_f, 40 % at "
     "-0.9994, are a real trade-off): the data determine only their "
     "combination. A note where one of the two is determined (below 30 %): its standard error "
     "carries the trade-off, and weakly_determined judges the other.",
     "Fix or drop the one the finding names."},
    {K::kInputNoise, "input_noise", S::kWarning,
     "A measured input carries white noise (robust second and third differences agree) and "
     "the fit's residuals are coloured, in a stage that left the noise out of its standard "
     "errors (`uncertainty: {input_noise: off}`, its refits failed, or it has more than 200 "
     "experiments/segments or 2e6 samples). By default a stage "
     "adds the spread of refits with the noise added again to its standard errors and says "
     "so in its notes.",
     "Keep `uncertainty: {input_noise: auto}`, or declare the input under `input_noise:` (a "
     "latent input)."},
    {K::kFailedFit, "failed_fit", S::kFailure,
     "A simulated output predicts its record worse than the record's mean (R^2 < 0) or worse "
     "than holding the record's first value (MAE above the hold MAE), where the record varies "
     "beyond its noise (its SD above 3 x its noise level). Judged against what the record "
     "allows, never against a noise level alone: smooth model-test records have a tiny noise "
     "level that any real fit exceeds 100-fold.",
     "The structure, a start, or the data are wrong for this record: look at its trace."},
    {K::kPoorFit, "poor_fit", S::kWarning,
     "A simulated output that did not fail explains less than half of its record's variation "
     "beyond the noise: fit below 50 % (residual RMS above half the record's SD), where the "
     "record varies beyond its noise (its SD above 3 x its noise level).",
     "Expected of a start stage; in the last stage, look for missing dynamics or a wrong "
     "minimum (a global start)."},
    {K::kColouredResiduals, "coloured_residuals", S::kInfo,
     "Residuals are coloured (Ljung-Box p < 0.01, and the lag-1 autocorrelation beyond its 99 % "
     "band +-2.58/sqrt(N)): it matters for the standard errors (narrow_intervals says when). "
     "A warning where the structure is strong, beyond what noise gives: a lag-1 above 0.3 with "
     "an RMSE above 1.05 x the record's noise level (correct structures fitted to noisy records "
     "stay below 0.06 and 1.03 x where the input is clean; wrong structures, held parameters "
     "and unmodelled disturbances reach 0.3-0.95 and 1.2-2.1 x). The RMSE is taken without the "
     "part that "
     "noise on a measured input can make (the 99 % quantile over the input noise refits): "
     "a rudder's noise integrated into the heading is noise, not structure. A sensor's own slow "
     "noise (a compass's error with a time constant of seconds, the independent corpus's "
     "correct_coloured_heading_noise class) looks the same: the warning fires on every such "
     "run and says so where no residual is correlated with the inputs.",
     "A note: for the intervals use sandwich_hac. A warning: the model leaves out what drives "
     "the residual; try a richer structure (vesselid select), free what is held, or model the "
     "disturbance (`noise: auto`, the filter-error method: sensor noise, waves and gusts "
     "identified with the ship, told from missing structure by its innovations). If the "
     "residuals are not correlated with the inputs, log the sensor at rest: noise that wanders "
     "there is the sensor's, and the intervals are too narrow."},
    {K::kInputCorrelatedResiduals, "input_correlated_residuals", S::kInfo,
     "Residuals correlate with past inputs: dynamics the model leaves out, or noise on a "
     "measured input.",
     "Consider a richer structure or input_noise."},
    {K::kNotAdmissible, "not_admissible", S::kWarning,
     "The estimate breaks a physical condition over the range the data cover (mass matrix not "
     "positive definite, damping that feeds energy in at a speed the data reach, a thrust law "
     "not monotone in its input). A failure for the final values.",
     "Bound the offending parameter or fix the structure."},
    {K::kUnsupportedStructure, "unsupported_structure", S::kWarning,
     "A structural feature of the estimate that the model family's physics say the data do "
     "not support, over the commands and speeds the records reach. Input-gain model: a dead "
     "zone whose branch bends the wrong way beyond it (ahead k_f < 0; astern k_r1 < 0 or "
     "k_r2 < 0): a propeller's thrust grows at least linearly past its zone, so the zone and "
     "the bend together stand in for a thrust law the model lacks.",
     "Try the law the message names (thrust: [\"n|n|\"], dead_zone: false) and compare the "
     "held-out fits."},
    {K::kStageSetAside, "stage_set_aside", S::kWarning,
     "Under `final: best_validation` a stage predicted its held-out records worse than its "
     "baseline (more runs diverged, or a mean MAE ratio above 1.01 on the runs both simulate) "
     "and its estimates were set aside; the next stage and the final values take the baseline's "
     "values. The baseline is the better on the held-out records of the stage's start and the "
     "previous stages' values (they differ where a stage restarts a parameter from the config). "
     "More diverging runs do not set a stage aside when its start is far worse (over twice "
     "its MAE) on the runs both simulate: a guard never falls back to values worse still. "
     "With no stage kept the final values are the config's start values: a failure.",
     "Look at the stage's held-out fits; the stage may need other records or bounds."},
    {K::kHeldOutWorse, "held_out_worse", S::kWarning,
     "A kept stage predicts its held-out records worse than its baseline (the better of its "
     "start and the previous stages' values; mean MAE ratio above 1.01, or more runs "
     "diverged).",
     "Use `final: best_validation` or look at the held-out traces."},
    {K::kHeldOutOutputWorse, "held_out_output_worse", S::kWarning,
     "A stage better over all held-out outputs predicts one of them worse than its baseline "
     "(the better of its start and the previous stages' values; MAE ratio above 1.01).",
     "Look at that output's held-out trace."},
    {K::kHeldOutDiverged, "held_out_diverged", S::kFailure,
     "The simulation of a held-out record diverged with the stage's estimate.",
     "The estimate is unstable outside the training records."},
    {K::kHeldOutFreeRunFailed, "held_out_free_run_failed", S::kWarning,
     "The velocity validation of a kept stage (each held-out record simulated whole from the "
     "data's state, with the per-experiment values its held-out fit estimated) predicts a "
     "velocity worse than its mean: free-run R2 < 0. A failure for "
     "the final values. Good fits of the shipped campaigns reach R2 0.98 and above.",
     "Read the held-out free-run traces; the model's structure or its thrust law may not hold "
     "outside the training runs."},
    {K::kFinalHeldOutFailed, "final_held_out_failed", S::kFailure,
     "The final values' simulation of the held-out records diverges, or predicts an output "
     "worse than holding its first measured value (pooled MAE ratio above 1).",
     "Do not use the model for prediction as it is."},
    {K::kImplausibleStart, "implausible_start", S::kWarning,
     "A held-out run was scored from a refitted start (`held_out: {start: refitted}`) that "
     "puts a measured state more than `implausible_sds` (5) noise SDs from its measurement: "
     "its fit leans on the start, not on the parameters. The finding gives the run's figures "
     "from the measured start beside it.",
     "Judge the model by the figures from the measured start (the default, `start: measured`)."},
    {K::kHeldOutBeyondBand, "held_out_beyond_band", S::kWarning,
     "A held-out run of the final validation, flown from its measured start, has an error that "
     "no adjustment of the estimates and of its start within their covariance explains: "
     "Q = min_d |r - S d|^2 / sigma^2 + d' P^-1 d over its scored samples, with sigma^2 the "
     "training fit's mean square residual per output (raised to the run's own noise level where "
     "that is higher), above (1 - s) 1.25 + s 4.6 times the samples, s the training residuals' "
     "input-noise share. Correct fits of the independent corpus stay at 0.9-1.3; structures "
     "that fit their training run and miss the next (speed loss, an unmodelled nonlinearity or "
     "disturbance) reach 1.4-50. `prediction_band` in results.json holds each run's figures.",
     "Compare the run's traces with the training runs': what it shows that they do not (larger "
     "rudder angles, speed loss in the turns, another speed) is what the model's structure or "
     "its training data lack; add that to the structure or to the training runs."},
    {K::kWorseThanReference, "worse_than_reference", S::kWarning,
     "The final values predict the final validation's held-out runs, flown from their "
     "measured starts, worse than the reference model `final_validation: {reference: "
     "<folder>}` names (another run's results.json, flown alike): more runs diverge, or the "
     "mean over the outputs of the MAE ratio final / reference is above 1.01. A model "
     "identified from fewer runs, or with another structure's restriction, is held against "
     "the one the user already trusts.",
     "Keep the reference model, or find out what the new runs or settings cost: identify "
     "from the reference's runs and the new ones together."},
};

// The value of `values` whose name is `text`.
template <class E, size_t N>
bool FromName(const std::string& text, const E (&values)[N], const char* (*name)(E), E* out) {
  for (E v : values) {
    if (text == name(v)) {
      *out = v;
      return true;
    }
  }
  return false;
}

const S kSeverities[] = {S::kInfo, S::kWarning, S::kFailure};
const Verdict kVerdicts[] = {Verdict::kGood, Verdict::kDoubtful, Verdict::kFailed};

}  // namespace

const char* FindingSeverityToString(FindingSeverity severity) {
  switch (severity) {
    case S::kInfo: return "info";
    case S::kWarning: return "warning";
    case S::kFailure: return "failure";
  }
  return "?";
}

bool StringToFindingSeverity(const std::string& text, FindingSeverity* severity) {
  return FromName(text, kSeverities, FindingSeverityToString, severity);
}

const char* FindingKindToString(FindingKind kind) {
  for (const Row& row : kRows) {
    if (row.kind == kind) return row.name;
  }
  return "?";
}

bool StringToFindingKind(const std::string& text, FindingKind* kind) {
  for (const Row& row : kRows) {
    if (text == row.name) {
      *kind = row.kind;
      return true;
    }
  }
  return false;
}

const std::vector<FindingRule>& FindingCatalogue() {
  static const std::vector<FindingRule> catalogue = [] {
    std::vector<FindingRule> rules;
    for (const Row& row : kRows) rules.push_back({row.kind, row.severity, row.rule, row.advice});
    return rules;
  }();
  return catalogue;
}

const FindingRule& RuleOf(FindingKind kind) {
  for (const FindingRule& rule : FindingCatalogue()) {
    if (rule.kind == kind) return rule;
  }
  return FindingCatalogue().front();
}

Finding MakeFinding(FindingKind kind, std::string message) {
  Finding f;
  f.kind = kind;
  f.severity = RuleOf(kind).severity;
  f.message = std::move(message);
  return f;
}

void AddFindingOnce(Finding finding, std::vector<Finding>* findings) {
  for (const Finding& f : *findings) {
    if (f.kind == finding.kind && f.experiment == finding.experiment &&
        f.segment == finding.segment && f.message == finding.message) {
      return;
    }
  }
  findings->push_back(std::move(finding));
}

std::string FindingCatalogueMarkdown() {
  std::string out =
      "| kind | severity | rule | what to do |\n"
      "|---|---|---|---|\n";
  for (const Row& row : kRows) {
    out += std::string("| `") + row.name + "` | " + FindingSeverityToString(row.severity) + " | " +
           row.rule + " | " + row.advice + " |\n";
  }
  return out;
}

const char* VerdictToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kGood: return "good";
    case Verdict::kDoubtful: return "doubtful";
    case Verdict::kFailed: return "failed";
  }
  return "?";
}

bool StringToVerdict(const std::string& text, Verdict* verdict) {
  return FromName(text, kVerdicts, VerdictToString, verdict);
}

Verdict Worse(Verdict a, Verdict b) { return static_cast<int>(a) > static_cast<int>(b) ? a : b; }

Verdict VerdictOf(const std::vector<Finding>& findings) {
  Verdict verdict = Verdict::kGood;
  for (const Finding& f : findings) {
    if (f.severity == S::kFailure) verdict = Verdict::kFailed;
    if (f.severity == S::kWarning) verdict = Worse(verdict, Verdict::kDoubtful);
  }
  return verdict;
}

std::string DescribeFinding(const Finding& f) {
  std::string where;
  auto add = [&where](const std::string& label, const std::string& value) {
    if (value.empty()) return;
    where += (where.empty() ? "" : ", ") + label + value;
  };
  add("stage ", f.stage.empty() ? "" : (f.stage == "final" ? "final" : "'" + f.stage + "'"));
  add("experiment ", f.experiment.empty() ? "" : "'" + f.experiment + "'");
  add("segment ", f.segment);
  add("", f.parameter);
  add("output ", f.output);
  add("input ", f.input);
  std::string text = std::string(FindingSeverityToString(f.severity)) + " [" +
                     FindingKindToString(f.kind) + "] " + (where.empty() ? "" : where + ": ") +
                     f.message;
  if (f.count > 1) text += " (x" + std::to_string(f.count) + ")";
  return text;
}

void SortFindings(std::vector<Finding>* findings) {
  std::stable_sort(findings->begin(), findings->end(), [](const Finding& a, const Finding& b) {
    return std::make_tuple(-static_cast<int>(a.severity), static_cast<int>(a.kind), a.stage,
                           a.experiment) < std::make_tuple(-static_cast<int>(b.severity),
                                                           static_cast<int>(b.kind), b.stage,
                                                           b.experiment);
  });
}

}  // namespace vesselid
