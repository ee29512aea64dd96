// Data-partition sensitivity of one stage (seed 000, Tables 4-9): how much the identified
// model and its validation metrics depend on which data it was fitted on.
//
// A pool of units is split at random into a validation part of round(s_v N) and a training
// part of round(s_t N) units, the rest unused, where a unit is
//   segments: a whole record (the validation part can be simulated: free-run metrics), or
//   points:   one (record, sample) pair.
// The stage is fitted on the training part and measured on both parts:
//   least squares (partition_study_least_squares.cc): the pool holds regression records
//     (each segment its own), points act through each record's `use` mask; the stage's
//     regression (RunLeastSquares) is measured by one-step-ahead prediction
//       x^(k+1) = x(k) + dt phi(k) theta(p)
//     of each regressed state (each equation on its own regions, as the stage fits it);
//   output error (partition_study_output_error.cc): the pool holds the stage's prepared
//     experiments (each segment its own), points remove samples from an experiment's
//     comparison; the stage is solved as configured on the training part and its outputs
//     are measured (RMSE, MAE, R^2, fit %) on the fit and on the validation part simulated
//     with the fitted parameters: held-out experiments from initial states estimated with
//     the parameters held (segments), held-out samples of the fitted simulation (points).
//
//   (a) repeated: `partitions` splits with s_t = 1 - s_v, repetition r drawn with seed + r:
//       mean +- SD over the splits of the metrics (and of every parameter);
//   (b) shares: one split (seed) per training share s_t, s_v fixed: training against
//       validation metrics as the training data shrink.
//
// Every split is a case of study_runner.h (threads and MPI ranks), a pure function of its
// index serialised to JSON; the tables are made on rank 0 from the merged cases, so the
// numbers do not depend on how many threads or ranks ran them.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "engine/model/model.h"
#include "engine/solve/metrics.h"
#include "engine/solve/parameter.h"
#include "engine/study/partition_options.h"
#include "engine/study/study_runner.h"
#include "nlohmann/json.hpp"

namespace vesselid {

struct RunConfig;
struct StageConfig;

// One split and what the stage made of it.
struct PartitionOutcome {
  std::string method;  // segments or points
  unsigned seed = 0;
  double training_share = 0.0;
  // Records (least squares) or experiments (output error) with at least one unit, and the
  // samples of the units.
  int training_records = 0, validation_records = 0;
  int training_samples = 0, validation_samples = 0;
  bool usable = false;
  std::string message;             // why the split failed (usable false), or a note
  std::vector<double> parameters;  // every model parameter, model order
  // One ChannelMetrics per channel of StudyResult::channels.
  //   least squares: one-step prediction of the training and the validation part;
  //   output error: the fit of the training part, the simulated validation part.
  std::vector<ChannelMetrics> training;
  std::vector<ChannelMetrics> validation;
  // Least squares only: validation records simulated whole (segments), and x^(k+1) = x(k)
  // on the validation part's one-step samples: no model at all, the reference a one-step
  // R^2 near 1 has to be read against.
  std::vector<ChannelMetrics> free_run;
  std::vector<ChannelMetrics> persistence;
  // Output error: final cost of the training fit; NaN for least squares.
  double cost = std::numeric_limits<double>::quiet_NaN();
  double time_seconds = 0.0;
};

struct StudyResult {
  StudyOptions options;  // as run (stage and experiments resolved)
  std::string kind;      // least_squares or output_error
  std::string model;
  int records = 0;  // units of a split by segments: records or experiments
  int samples = 0;  // units of a split by points
  int duplicates = 0;                      // second copies of a segment, dropped
  std::vector<std::string> channels;       // regressed states or compared outputs
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

// The stage a partition study of `name` studies (the default rule of StudyOptions::stage);
// null when the run has no such stage.
const StageConfig* PartitionStudyStage(const RunConfig& config, const std::string& name);

// Runs tables (a) and (b), the splits as cases over threads and ranks. On rank 0 `result`
// holds the study; other ranks get an empty result (no splits). A split that cannot be
// fitted is recorded with its message; the study fails (false, `error`) only on bad options,
// a missing stage or unreadable data. `progress` is told after each case of this rank.
bool RunPartitionStudy(const RunConfig& config, const StudyOptions& options,
                       const CaseOptions& execution, StudyResult* result, std::string* error,
                       const CaseProgress& progress = nullptr);

// Tables (a), (b) and the parameter spread as text; the same, with every split, as JSON.
std::string StudyResultToText(const StudyResult& result);
nlohmann::json StudyResultToJson(const StudyResult& result);

// Internals shared by the partition study's source files.
namespace partition_internal {

enum class SplitPart : char { kUnused, kTraining, kValidation };

// Units 0..count-1 split by a seeded shuffle: the first round(validation_share * count) are
// validation, the next `training` units training, the rest unused.
std::vector<SplitPart> DrawSplit(int count, double validation_share, int training,
                                 unsigned seed);

// The units of one kind of stage and the fit of a split of them. Fit is const and
// thread-safe: splits run concurrently.
class PartitionPool {
 public:
  virtual ~PartitionPool() = default;
  // Units of a split by `method`: records (segments) or samples (points).
  virtual int Units(const std::string& method) const = 0;
  // The stage fitted on the training units of `parts` (one per unit) and measured; the
  // caller fills method, seed, training share and time.
  virtual PartitionOutcome Fit(const std::string& method,
                               const std::vector<SplitPart>& parts) const = 0;
};

// Pools of a least-squares and an output-error stage. They resolve result->options (stage,
// experiments) and fill result's description (kind, model, pool counts, channels,
// parameters, held); null with `error` on missing stage or unreadable data.
std::unique_ptr<PartitionPool> LeastSquaresPool(const RunConfig& config, const StageConfig& stage,
                                                StudyResult* result, std::string* error);
std::unique_ptr<PartitionPool> OutputErrorPool(const RunConfig& config, const StageConfig& stage,
                                               StudyResult* result, std::string* error);

// A split's case record (the JSON of StudyResultToJson's splits) and back; `result` gives
// the channel and parameter names.
nlohmann::json OutcomeToJson(const StudyResult& result, const PartitionOutcome& outcome);
PartitionOutcome OutcomeFromJson(const StudyResult& result, const nlohmann::json& j);

}  // namespace partition_internal
}  // namespace vesselid
