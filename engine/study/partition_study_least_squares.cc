// Partition study of a least-squares stage: regression records as units, each split fitted
// by the stage's regression and measured by one-step prediction (partition_study.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "engine/regression/least_squares.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/velocity_validation.h"
#include "engine/study/partition_study.h"

namespace vesselid {
namespace partition_internal {
namespace {

int CountUsed(const RegressionRecord& record) {
  return static_cast<int>(std::count(record.use.begin(), record.use.end(), true));
}

// One-step "prediction" without a model, x^(k+1) = x(k), at the samples OneStepMetrics
// measures (selected, in the equation's regions, with a finite derivative).
std::vector<ChannelMetrics> PersistenceMetrics(const ModelHandle& model,
                                               const LeastSquaresOptions& options,
                                               const std::vector<RegressionRecord>& records) {
  const RegressionForm& form = *model.regression_form();
  std::vector<ChannelMetrics> metrics;
  for (size_t i = 0; i < form.states.size(); ++i) {
    const int s = form.states[i];
    const std::vector<int> none;
    const std::vector<int>& regions = i < options.regions.size() ? options.regions[i] : none;
    MetricAccumulator accumulator;
    for (const RegressionRecord& record : records) {
      for (int k = 0; k + 1 < record.size(); ++k) {
        const bool in_region = regions.empty() || std::find(regions.begin(), regions.end(),
                                                            record.region[k]) != regions.end();
        if (record.use[k] && in_region && std::isfinite(record.xdot(k, s))) {
          accumulator.Add(record.x(k, s), record.x(k + 1, s));
        }
      }
    }
    metrics.push_back(accumulator.Finish("persistence", model.info().states[s]));
  }
  return metrics;
}

class LeastSquaresPartitionPool : public PartitionPool {
 public:
  const RunConfig* config = nullptr;
  const StageConfig* stage = nullptr;
  const ModelHandle* model = nullptr;
  std::vector<ParameterSpec> specs;
  std::vector<RegressionRecord> pool;
  TrajectoryCache cache;
  int samples = 0;  // selected samples of the pool (the units of a split by points)

  int Units(const std::string& method) const override {
    return method == "segments" ? static_cast<int>(pool.size()) : samples;
  }

  PartitionOutcome Fit(const std::string& method,
                       const std::vector<SplitPart>& parts) const override {
    PartitionOutcome outcome;
    std::vector<RegressionRecord> training, validation;
    ApplySplit(method, parts, &training, &validation);
    outcome.training_records = static_cast<int>(training.size());
    outcome.validation_records = static_cast<int>(validation.size());
    for (const RegressionRecord& r : training) outcome.training_samples += CountUsed(r);
    for (const RegressionRecord& r : validation) outcome.validation_samples += CountUsed(r);
    if (training.empty() || validation.empty()) {
      outcome.message = "empty training or validation part";
      return outcome;
    }
    const LeastSquaresOptions& options = stage->least_squares;
    LeastSquaresResult ls;
    LeastSquaresSummary summary;
    if (!RunLeastSquares(*model, specs, options, &training, &ls, &summary)) {
      outcome.message = summary.message;
      return outcome;
    }
    std::string error;
    if (!OneStepMetrics(*model, ls.values, options, &training, "training", &outcome.training,
                        &error) ||
        !OneStepMetrics(*model, ls.values, options, &validation, "validation",
                        &outcome.validation, &error)) {
      outcome.message = error;
      return outcome;
    }
    outcome.parameters = ls.values;
    outcome.persistence = PersistenceMetrics(*model, options, validation);
    outcome.usable = true;
    // Free run of whole held-out records; a diverging one leaves the split's one-step metrics.
    std::vector<std::string> diverged;
    if (method == "segments" &&
        (!FreeRunMetrics(*config, *model, ls.values, cache, VelocitySteps{}, &validation,
                         &outcome.free_run, &diverged, &error) ||
         !diverged.empty())) {
      outcome.free_run.clear();
      outcome.message = diverged.empty() ? "free run: " + error : diverged.front();
    }
    return outcome;
  }

 private:
  // The training and validation records of a split.
  void ApplySplit(const std::string& method, const std::vector<SplitPart>& parts,
                  std::vector<RegressionRecord>* training,
                  std::vector<RegressionRecord>* validation) const {
    if (method == "segments") {
      for (size_t r = 0; r < pool.size(); ++r) {
        if (parts[r] == SplitPart::kTraining) training->push_back(pool[r]);
        if (parts[r] == SplitPart::kValidation) validation->push_back(pool[r]);
      }
      return;
    }
    // Points: unit j is the j-th selected (record, sample) pair in pool order; a record takes
    // part with the samples it has in that part (its `use` mask), whole for its regressors.
    int unit = 0;
    for (const RegressionRecord& record : pool) {
      RegressionRecord train = record, held = record;
      for (int k = 0; k < record.size(); ++k) {
        if (!record.use[k]) continue;
        const SplitPart part = parts[unit++];
        train.use[k] = part == SplitPart::kTraining;
        held.use[k] = part == SplitPart::kValidation;
      }
      if (CountUsed(train) > 0) training->push_back(std::move(train));
      if (CountUsed(held) > 0) validation->push_back(std::move(held));
    }
  }
};

}  // namespace

std::unique_ptr<PartitionPool> LeastSquaresPool(const RunConfig& config, const StageConfig& stage,
                                                StudyResult* result, std::string* error) {
  auto c = std::make_unique<LeastSquaresPartitionPool>();
  StudyOptions& o = result->options;
  c->config = &config;
  c->stage = &stage;
  c->model = stage.model ? stage.model.get() : config.model.get();
  const ModelInfo& info = c->model->info();
  if (o.experiments.empty()) {
    for (const auto* list : {&stage.experiments, &stage.validation}) {
      for (const std::string& name : *list) {
        if (std::find(o.experiments.begin(), o.experiments.end(), name) == o.experiments.end()) {
          o.experiments.push_back(name);
        }
      }
    }
  }
  for (const std::string& name : o.experiments) {
    if (config.FindExperiment(name) == nullptr) {
      *error = "no experiment named '" + name + "'";
      return nullptr;
    }
  }
  c->specs = StudyParameterSpecs(stage, info);
  for (const ParameterSpec& spec : c->specs) {
    if (spec.role != ParameterRole::kFixed && !spec.IsValid("stage '" + o.stage + "'", error)) {
      return nullptr;
    }
  }
  std::vector<RegressionRecord> records;
  if (!PrepareRegressionRecords(config, o.experiments, *c->model, stage.regression_data,
                                &c->cache, &records, error)) {
    return nullptr;
  }
  // A segment listed by two experiments of the pool (held-out segments and their copy with
  // reference outputs) is one record, the first.
  std::set<std::tuple<std::string, double, double>> seen;
  for (RegressionRecord& record : records) {
    if (record.size() == 0) continue;
    const auto key = std::make_tuple(config.FindExperiment(record.record)->file, record.t.front(),
                                     record.t.back());
    if (seen.insert(key).second) {
      c->pool.push_back(std::move(record));
    } else {
      ++result->duplicates;
    }
  }
  // File and time order: a split by segments with seed s then holds out the segments an
  // experiment's `segments: {validation_share, seed: s}` holds out (RandomValidationMask).
  std::stable_sort(c->pool.begin(), c->pool.end(),
                   [&](const RegressionRecord& a, const RegressionRecord& b) {
                     const std::string& fa = config.FindExperiment(a.record)->file;
                     const std::string& fb = config.FindExperiment(b.record)->file;
                     return fa != fb ? fa < fb : a.t.front() < b.t.front();
                   });
  for (const RegressionRecord& record : c->pool) c->samples += CountUsed(record);
  if (c->pool.empty()) {
    *error = "the pool has no records";
    return nullptr;
  }
  result->kind = "least_squares";
  result->model = info.name;
  result->records = static_cast<int>(c->pool.size());
  result->samples = c->samples;
  for (int s : c->model->regression_form()->states) result->channels.push_back(info.states[s]);
  result->parameters = info.parameters;
  for (const ParameterSpec& spec : c->specs) {
    result->held.push_back(spec.role == ParameterRole::kFixed);
  }
  return c;
}

}  // namespace partition_internal
}  // namespace vesselid
