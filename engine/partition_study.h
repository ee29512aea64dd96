// Data-partition sensitivity of a least-squares stage (seed 000, Tables 4-9): how much the
// identified model and its validation metrics depend on which data it was fitted on.
//
// A pool of regression records (each segment its own record) is split at random into a
// validation part of round(s_v N) and a training part of round(s_t N) units, the rest unused,
// where a unit is
//   segments: a whole record (the validation part can be simulated: free-run metrics), or
//   points:   one (record, sample) pair, applied through each record's `use` mask.
// For each split the stage's regression (RunLeastSquares, its parameter specs and options)
// is fitted on the training part and measured by one-step-ahead prediction
//   x^(k+1) = x(k) + dt phi(k) theta(p)
// of each regressed state on the training and the validation part (each equation on its
// own regions, as the stage fits it).
//
//   (a) repeated: `partitions` splits with s_t = 1 - s_v, repetition r drawn with seed + r:
//       mean +- SD over the splits of MAE and R^2 (and of every parameter);
//   (b) shares: one split (seed) per training share s_t, s_v fixed: training against
//       validation metrics as the training data shrink.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/metrics.h"
#include "engine/model.h"
#include "engine/parameter.h"
#include "nlohmann/json.hpp"

namespace vesselid {

struct RunConfig;
struct StageConfig;

struct StudyOptions {
  // Name of a least_squares stage of the run; empty: the first one.
  std::string stage;
  // Pool of records: config experiment names, each expanded to its segments; empty: the
  // stage's experiments followed by its validation experiments.
  std::vector<std::string> experiments;
  // Repetitions of table (a); repetition r splits with seed + r.
  int partitions = 20;
  // Share of the pool's units held out for validation, in (0, 1).
  double validation_share = 0.3;
  // Training shares of table (b); validation_share + each share <= 1.
  std::vector<double> training_shares = {0.7, 0.6, 0.5};
  // Units of a split: "segments" (whole records) and/or "points" (samples).
  std::vector<std::string> methods = {"segments", "points"};
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

// One split and what the stage's regression made of it.
struct PartitionOutcome {
  std::string method;  // segments or points
  unsigned seed = 0;
  double training_share = 0.0;
  int training_records = 0, validation_records = 0;  // records with at least one unit
  int training_samples = 0, validation_samples = 0;  // grid samples of the units
  bool usable = false;
  std::string message;             // why the split failed (usable false)
  std::vector<double> parameters;  // every model parameter, model order
  // One ChannelMetrics per regressed state (output = state name).
  std::vector<ChannelMetrics> training;    // one-step, training part
  std::vector<ChannelMetrics> validation;  // one-step, validation part
  std::vector<ChannelMetrics> free_run;    // validation records simulated whole (segments)
  // x^(k+1) = x(k) on the validation part's one-step samples: no model at all, the
  // reference a one-step R^2 near 1 has to be read against.
  std::vector<ChannelMetrics> persistence;
  double time_seconds = 0.0;
};

struct StudyResult {
  StudyOptions options;  // as run (stage and experiments resolved)
  std::string model;
  int records = 0;  // in the pool
  int samples = 0;
  int duplicates = 0;                      // second copies of a segment, dropped
  std::vector<std::string> states;         // regressed states
  std::vector<std::string> parameters;     // model order
  std::vector<bool> held;                  // parameters the stage does not estimate
  std::vector<PartitionOutcome> repeated;  // (a): per method, `partitions` splits
  std::vector<PartitionOutcome> shares;    // (b): per training share, per method
  double time_seconds = 0.0;
};

// Parameter specs of a least-squares stage in model order, as the study fits them: a listed
// parameter keeps its spec (its start the model default when it starts from the previous
// stage), an unlisted one is held at the model default.
std::vector<ParameterSpec> StudyParameterSpecs(const StageConfig& stage, const ModelInfo& info);

// Told after every split: a one-line description (progress output).
using StudyProgress = std::function<void(const std::string& line)>;

// Runs tables (a) and (b). A split that cannot be fitted is recorded with its message; the
// study fails (false, `error`) only on bad options, a missing stage or unreadable data.
bool RunPartitionStudy(const RunConfig& config, const StudyOptions& options, StudyResult* result,
                       std::string* error, const StudyProgress& progress = nullptr);

// Tables (a), (b) and the parameter spread as text; the same, with every split, as JSON.
std::string StudyResultToText(const StudyResult& result);
nlohmann::json StudyResultToJson(const StudyResult& result);

}  // namespace vesselid
