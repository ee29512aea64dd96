// Partition study of an output-error stage (partition_study.h): the stage's experiments as
// units, each split solved as the stage is configured (SolveStudyStage, from the starts the
// run carries into it) on the training part, the outputs measured per channel on
//   training:   the fit, each training experiment from its estimated initial state;
//   validation: segments: the held-out experiments simulated with the fitted parameters, their
//               free initial states estimated with the parameters held (HeldOutProblem);
//               points: the held-out samples of the training experiments' fitted simulation
//               (the same grid: removing samples keeps every node).
#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "engine/run/held_out.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/stage_weights.h"
#include "engine/study/partition_study.h"
#include "engine/study/study_stage.h"

namespace vesselid {
namespace partition_internal {
namespace {

// Accumulators per model output, one set per SplitPart.
using ChannelSums = std::vector<std::vector<MetricAccumulator>>;

ChannelSums MakeSums(int outputs) {
  return ChannelSums(3, std::vector<MetricAccumulator>(outputs));
}

std::vector<MetricAccumulator>& SumsOf(ChannelSums* sums, SplitPart part) {
  return (*sums)[static_cast<int>(part)];
}

// Simulates `experiment` with p and x0 and adds each sample's error to the sums of its part:
// parts[i] for sample i, or `all` for every sample when `parts` is null. False if the
// simulation diverges.
bool AddSimulated(const ModelHandle& model, const Experiment& experiment,
                  const std::vector<double>& p, const std::vector<double>& x0,
                  const SplitPart* parts, SplitPart all, ChannelSums* sums, std::string* error) {
  const ModelInfo& info = model.info();
  const int ny = static_cast<int>(info.outputs.size());
  std::vector<double> outputs;
  if (!model.SimulateOutputs(experiment, p.data(), x0.data(), &outputs)) {
    *error = "simulation of experiment '" + experiment.name + "' diverges";
    return false;
  }
  for (int k = 0; k < experiment.num_nodes(); ++k) {
    for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1]; ++i) {
      const SplitPart part = parts != nullptr ? parts[i] : all;
      if (part == SplitPart::kUnused) continue;
      const ExperimentSample& s = experiment.samples[i];
      SumsOf(sums, part)[s.output].Add(outputs[static_cast<size_t>(k) * ny + s.output], s.value,
                                       experiment.Wrapped(s.output));
    }
  }
  return true;
}

// Experiment `x` compared on the samples whose part is kTraining only (grid, inputs and
// initial states unchanged); with length normalisation its weights are those of an
// experiment built from these samples.
Experiment TrainingSamples(const Experiment& x, const SplitPart* parts, int outputs,
                           bool normalize) {
  Experiment t = x;
  t.samples.clear();
  t.output_sample_count.assign(outputs, 0);
  for (int k = 0; k < x.num_nodes(); ++k) {
    t.node_first_sample[k] = t.num_samples();
    for (int i = x.node_first_sample[k]; i < x.node_first_sample[k + 1]; ++i) {
      if (parts[i] != SplitPart::kTraining) continue;
      t.samples.push_back(x.samples[i]);
      ++t.output_sample_count[x.samples[i].output];
    }
  }
  t.node_first_sample[x.num_nodes()] = t.num_samples();
  if (normalize && t.num_samples() > 0) {
    const double scale = std::sqrt(static_cast<double>(x.num_samples()) / t.num_samples());
    for (ExperimentSample& s : t.samples) s.weight *= scale;
  }
  return t;
}

class OutputErrorPartitionPool : public PartitionPool {
 public:
  StudyStage stage;               // its experiments moved into `pool`
  std::vector<Experiment> pool;   // the units of a split by segments, file and time order
  std::vector<int> first_unit;    // points: unit of pool[e]'s first sample
  int samples = 0;                // the units of a split by points
  std::vector<int> channels;      // model outputs compared in the pool

  int Units(const std::string& method) const override {
    return method == "segments" ? static_cast<int>(pool.size()) : samples;
  }

  PartitionOutcome Fit(const std::string& method,
                       const std::vector<SplitPart>& parts) const override {
    return method == "segments" ? FitSegments(parts) : FitPoints(parts);
  }

 private:
  int NumOutputs() const { return static_cast<int>(stage.model->info().outputs.size()); }

  std::vector<ChannelMetrics> Finish(const std::vector<MetricAccumulator>& sums,
                                     const std::string& label) const {
    std::vector<ChannelMetrics> metrics;
    for (int c : channels) metrics.push_back(sums[c].Finish(label, stage.model->info().outputs[c]));
    return metrics;
  }

  // The stage solved on `training`: parameters, cost and nothing else; false with the
  // solve's message.
  bool Solve(std::vector<Experiment> training, PartitionOutcome* outcome,
             StudySolve* solve) const {
    *solve = SolveStudyStage(stage, std::move(training), stage.specs, stage.options);
    if (!solve->usable) {
      outcome->message = solve->message;
      return false;
    }
    outcome->cost = solve->summary.local().final_cost;
    // Model order; a per-experiment parameter as the first training experiment has it.
    outcome->parameters = solve->problem->ParametersOf(0);
    return true;
  }

  PartitionOutcome FitSegments(const std::vector<SplitPart>& parts) const {
    PartitionOutcome outcome;
    std::vector<Experiment> training, validation;
    for (size_t e = 0; e < pool.size(); ++e) {
      if (parts[e] == SplitPart::kUnused) continue;
      const bool train = parts[e] == SplitPart::kTraining;
      (train ? outcome.training_records : outcome.validation_records) += 1;
      (train ? outcome.training_samples : outcome.validation_samples) += pool[e].num_samples();
      (train ? training : validation).push_back(pool[e]);
    }
    if (training.empty() || validation.empty()) {
      outcome.message = "empty training or validation part";
      return outcome;
    }
    StudySolve solve;
    if (!Solve(std::move(training), &outcome, &solve)) return outcome;
    const OutputErrorProblem& fitted = *solve.problem;
    ChannelSums sums = MakeSums(NumOutputs());
    std::string error;
    for (int j = 0; j < static_cast<int>(fitted.experiments().size()); ++j) {
      if (!AddSimulated(*stage.model, fitted.experiments()[j], fitted.ParametersOf(j),
                        fitted.InitialStateOf(j), nullptr, SplitPart::kTraining, &sums, &error)) {
        outcome.message = error;
        return outcome;
      }
    }
    outcome.training = Finish(SumsOf(&sums, SplitPart::kTraining), "training");
    outcome.usable = true;
    // Free run of the held-out experiments; one that cannot be simulated leaves the split
    // without validation metrics, said in its message.
    const std::unique_ptr<OutputErrorProblem> held =
        HeldOutProblem(*stage.model, std::move(validation), stage.stage->problem.free_initial_states,
                       stage.options.local, outcome.parameters, &error);
    bool simulated = held != nullptr;
    for (int j = 0; simulated && j < static_cast<int>(held->experiments().size()); ++j) {
      simulated = AddSimulated(*stage.model, held->experiments()[j], held->ParametersOf(j),
                               held->InitialStateOf(j), nullptr, SplitPart::kValidation, &sums,
                               &error);
    }
    if (simulated) {
      outcome.validation = Finish(SumsOf(&sums, SplitPart::kValidation), "validation");
    } else {
      outcome.message = "validation: " + error;
    }
    return outcome;
  }

  PartitionOutcome FitPoints(const std::vector<SplitPart>& parts) const {
    PartitionOutcome outcome;
    const bool normalize =
        StageExperimentOptions(*stage.config, *stage.stage).normalize_by_length;
    std::vector<Experiment> training;
    std::vector<int> source;  // pool index of each training experiment
    int left_out = 0;         // experiments with held-out samples but none to train on
    for (size_t e = 0; e < pool.size(); ++e) {
      const SplitPart* own = parts.data() + first_unit[e];
      const int n = pool[e].num_samples();
      const int held = static_cast<int>(std::count(own, own + n, SplitPart::kValidation));
      Experiment t = TrainingSamples(pool[e], own, NumOutputs(), normalize);
      if (t.num_samples() == 0) {
        left_out += held > 0;
        continue;
      }
      ++outcome.training_records;
      outcome.training_samples += t.num_samples();
      outcome.validation_records += held > 0;
      outcome.validation_samples += held;
      training.push_back(std::move(t));
      source.push_back(static_cast<int>(e));
    }
    if (training.empty() || outcome.validation_samples == 0) {
      outcome.message = "empty training or validation part";
      return outcome;
    }
    StudySolve solve;
    if (!Solve(std::move(training), &outcome, &solve)) return outcome;
    const OutputErrorProblem& fitted = *solve.problem;
    ChannelSums sums = MakeSums(NumOutputs());
    std::string error;
    for (size_t j = 0; j < source.size(); ++j) {
      // The whole experiment on the training experiment's grid, each sample to its part.
      const int e = source[j];
      if (!AddSimulated(*stage.model, pool[e], fitted.ParametersOf(static_cast<int>(j)),
                        fitted.InitialStateOf(static_cast<int>(j)), parts.data() + first_unit[e],
                        SplitPart::kUnused, &sums, &error)) {
        outcome.message = error;
        return outcome;
      }
    }
    outcome.training = Finish(SumsOf(&sums, SplitPart::kTraining), "training");
    outcome.validation = Finish(SumsOf(&sums, SplitPart::kValidation), "validation");
    outcome.usable = true;
    if (left_out > 0) {
      outcome.message = std::to_string(left_out) +
                        " experiments without training samples: their held-out samples are "
                        "not measured";
    }
    return outcome;
  }
};

}  // namespace

std::unique_ptr<PartitionPool> OutputErrorPool(const RunConfig& config, const StageConfig& stage,
                                               StudyResult* result, std::string* error) {
  auto c = std::make_unique<OutputErrorPartitionPool>();
  StudyOptions& o = result->options;
  if (!PrepareStudyStage(config, stage.options.name, &c->stage, error)) return nullptr;
  const ModelHandle& model = *c->stage.model;
  const ModelInfo& info = model.info();
  // The stage's experiments, then those the study adds.
  std::vector<std::string> names = stage.experiments, added;
  for (const std::string& name : o.experiments) {
    if (config.FindExperiment(name) == nullptr) {
      *error = "no experiment named '" + name + "'";
      return nullptr;
    }
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      names.push_back(name);
      added.push_back(name);
    }
  }
  o.experiments = names;
  std::vector<Experiment> experiments = std::move(c->stage.experiments);
  c->stage.experiments.clear();
  if (!added.empty()) {
    TrajectoryCache cache;
    std::vector<Experiment> more;
    if (!PrepareExperiments(config, added, model, StageExperimentOptions(config, stage), &cache,
                            &more, error)) {
      *error = "stage '" + stage.options.name + "': " + *error;
      return nullptr;
    }
    for (Experiment& e : more) experiments.push_back(std::move(e));
  }
  // A segment listed by two experiments of the pool is one experiment, the first; then file
  // and time order, as the least-squares pool (partition_study_least_squares.cc).
  auto file_of = [&](const Experiment& e) -> const std::string& {
    return config.FindExperiment(e.record)->file;
  };
  std::set<std::tuple<std::string, double, double>> seen;
  for (Experiment& e : experiments) {
    if (e.num_samples() == 0) continue;
    if (seen.insert(std::make_tuple(file_of(e), e.node_time.front(), e.node_time.back())).second) {
      c->pool.push_back(std::move(e));
    } else {
      ++result->duplicates;
    }
  }
  std::stable_sort(c->pool.begin(), c->pool.end(), [&](const Experiment& a, const Experiment& b) {
    const std::string& fa = file_of(a);
    const std::string& fb = file_of(b);
    return fa != fb ? fa < fb : a.node_time.front() < b.node_time.front();
  });
  if (c->pool.empty()) {
    *error = "the pool has no experiments with samples";
    return nullptr;
  }
  for (const Experiment& e : c->pool) {
    c->first_unit.push_back(c->samples);
    c->samples += e.num_samples();
  }
  for (size_t k = 0; k < info.outputs.size(); ++k) {
    bool compared = false;
    for (const Experiment& e : c->pool) compared |= e.output_sample_count[k] > 0;
    if (compared) {
      c->channels.push_back(static_cast<int>(k));
      result->channels.push_back(info.outputs[k]);
    }
  }
  result->kind = "output_error";
  result->model = info.name;
  result->records = static_cast<int>(c->pool.size());
  result->samples = c->samples;
  result->parameters = info.parameters;
  for (const ParameterSpec& spec : c->stage.specs) {
    result->held.push_back(spec.role == ParameterRole::kFixed);
  }
  return c;
}

}  // namespace partition_internal
}  // namespace vesselid
