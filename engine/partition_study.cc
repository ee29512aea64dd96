#include "engine/partition_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include "engine/config.h"
#include "engine/least_squares.h"
#include "engine/pipeline.h"
#include "engine/velocity_validation.h"

namespace vesselid {
namespace {

using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Part : char { kUnused, kTraining, kValidation };

// Units 0..count-1 split by a seeded shuffle: the first round(validation_share * count) are
// validation, the next `training` units training, the rest unused. Fisher-Yates with our own
// draws, as RandomValidationMask: std::shuffle's sequence is library-specific.
std::vector<Part> DrawSplit(int count, double validation_share, int training, unsigned seed) {
  std::vector<int> order(count);
  for (int i = 0; i < count; ++i) order[i] = i;
  std::mt19937 random(seed);
  for (int i = count - 1; i > 0; --i) {
    std::swap(order[i], order[random() % static_cast<unsigned>(i + 1)]);
  }
  const int nv = std::min(count, static_cast<int>(std::lround(validation_share * count)));
  const int nt = std::min(count - nv, training);
  std::vector<Part> parts(count, Part::kUnused);
  for (int i = 0; i < nv + nt; ++i) parts[order[i]] = i < nv ? Part::kValidation : Part::kTraining;
  return parts;
}

// Everything a split needs, prepared once.
struct StudyContext {
  const RunConfig* config = nullptr;
  const StageConfig* stage = nullptr;
  const ModelHandle* model = nullptr;
  std::vector<ParameterSpec> specs;
  std::vector<RegressionRecord> pool;
  TrajectoryCache cache;
  int samples = 0;  // selected samples of the pool (the units of a split by points)

  int Units(const std::string& method) const {
    return method == "segments" ? static_cast<int>(pool.size()) : samples;
  }
  // Training units of a split: all the rest (table a) or round(share * units) (table b).
  int TrainingUnits(const std::string& method, double validation_share, double share,
                    bool rest) const {
    const int units = Units(method);
    const int nv = static_cast<int>(std::lround(validation_share * units));
    return rest ? units - nv : static_cast<int>(std::lround(share * units));
  }
};

int CountUsed(const RegressionRecord& record) {
  return static_cast<int>(std::count(record.use.begin(), record.use.end(), true));
}

// The training and validation records of a split.
void ApplySplit(const StudyContext& c, const std::string& method, const std::vector<Part>& parts,
                std::vector<RegressionRecord>* training,
                std::vector<RegressionRecord>* validation) {
  training->clear();
  validation->clear();
  if (method == "segments") {
    for (size_t r = 0; r < c.pool.size(); ++r) {
      if (parts[r] == Part::kTraining) training->push_back(c.pool[r]);
      if (parts[r] == Part::kValidation) validation->push_back(c.pool[r]);
    }
    return;
  }
  // Points: unit j is the j-th selected (record, sample) pair in pool order; a record takes
  // part with the samples it has in that part (its `use` mask), whole for its regressors.
  int unit = 0;
  for (const RegressionRecord& record : c.pool) {
    RegressionRecord train = record, held = record;
    for (int k = 0; k < record.size(); ++k) {
      if (!record.use[k]) continue;
      const Part part = parts[unit++];
      train.use[k] = part == Part::kTraining;
      held.use[k] = part == Part::kValidation;
    }
    if (CountUsed(train) > 0) training->push_back(std::move(train));
    if (CountUsed(held) > 0) validation->push_back(std::move(held));
  }
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

PartitionOutcome RunSplit(StudyContext* c, const std::string& method, unsigned seed,
                          double validation_share, double training_share, bool rest) {
  const auto start_time = std::chrono::steady_clock::now();
  PartitionOutcome outcome;
  outcome.method = method;
  outcome.seed = seed;
  outcome.training_share = rest ? 1.0 - validation_share : training_share;
  const std::vector<Part> parts =
      DrawSplit(c->Units(method), validation_share,
                c->TrainingUnits(method, validation_share, training_share, rest), seed);
  std::vector<RegressionRecord> training, validation;
  ApplySplit(*c, method, parts, &training, &validation);
  outcome.training_records = static_cast<int>(training.size());
  outcome.validation_records = static_cast<int>(validation.size());
  for (const RegressionRecord& r : training) outcome.training_samples += CountUsed(r);
  for (const RegressionRecord& r : validation) outcome.validation_samples += CountUsed(r);
  auto finish = [&]() {
    outcome.time_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return outcome;
  };
  if (training.empty() || validation.empty()) {
    outcome.message = "empty training or validation part";
    return finish();
  }
  const ModelHandle& model = *c->model;
  const LeastSquaresOptions& options = c->stage->least_squares;
  LeastSquaresResult ls;
  LeastSquaresSummary summary;
  if (!RunLeastSquares(model, c->specs, options, &training, &ls, &summary)) {
    outcome.message = summary.message;
    return finish();
  }
  std::string error;
  if (!OneStepMetrics(model, ls.values, options, &training, "training", &outcome.training,
                      &error) ||
      !OneStepMetrics(model, ls.values, options, &validation, "validation", &outcome.validation,
                      &error)) {
    outcome.message = error;
    return finish();
  }
  outcome.parameters = ls.values;
  outcome.persistence = PersistenceMetrics(model, options, validation);
  outcome.usable = true;
  // Free run of whole held-out records; a diverging one leaves the split's one-step metrics.
  if (method == "segments" && !FreeRunMetrics(*c->config, model, ls.values, c->cache, &validation,
                                              &outcome.free_run, &error)) {
    outcome.free_run.clear();
    outcome.message = "free run: " + error;
  }
  return finish();
}

// "segments seed 3: validation one-step R2 u 0.991, v 0.952, r 0.987 (1.2 s)"
std::string ProgressLine(const PartitionOutcome& o, const std::string& table) {
  char text[160];
  std::snprintf(text, sizeof(text), "%s %s seed %u, training %.2f: ", table.c_str(),
                o.method.c_str(), o.seed, o.training_share);
  std::string line = text;
  if (!o.usable) return line + "failed: " + o.message;
  line += "validation one-step R2";
  for (const ChannelMetrics& m : o.validation) {
    std::snprintf(text, sizeof(text), " %s %.4f", m.output.c_str(), m.r2);
    line += text;
  }
  std::snprintf(text, sizeof(text), " (%.1f s)", o.time_seconds);
  return line + text + (o.message.empty() ? "" : "; " + o.message);
}

// Mean and sample standard deviation of the finite values (NaN SD below two values).
struct Spread {
  int n = 0;
  double mean = kNaN, sd = kNaN;
};

Spread SpreadOf(const std::vector<double>& values) {
  Spread s;
  double sum = 0.0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    sum += v;
    ++s.n;
  }
  if (s.n == 0) return s;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double ss = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) ss += (v - s.mean) * (v - s.mean);
  }
  s.sd = std::sqrt(ss / (s.n - 1));
  return s;
}

const std::vector<ChannelMetrics>& Metrics(const PartitionOutcome& o, const std::string& part) {
  return part == "training"      ? o.training
         : part == "validation"  ? o.validation
         : part == "persistence" ? o.persistence
                                 : o.free_run;
}

// mae, rmse or r2 of a channel; NaN without samples.
double MetricValue(const ChannelMetrics& m, const std::string& metric) {
  if (m.samples == 0) return kNaN;
  return metric == "mae" ? m.mae : metric == "rmse" ? m.rmse : m.r2;
}

// A metric of one state in one part over the usable splits of `outcomes`.
Spread MetricSpread(const std::vector<const PartitionOutcome*>& outcomes, const std::string& part,
                    const std::string& state, const std::string& metric) {
  std::vector<double> values;
  for (const PartitionOutcome* o : outcomes) {
    if (!o->usable) continue;
    for (const ChannelMetrics& m : Metrics(*o, part)) {
      if (m.output == state) values.push_back(MetricValue(m, metric));
    }
  }
  return SpreadOf(values);
}

Spread ParameterSpread(const std::vector<const PartitionOutcome*>& outcomes, size_t index) {
  std::vector<double> values;
  for (const PartitionOutcome* o : outcomes) {
    if (o->usable) values.push_back(o->parameters[index]);
  }
  return SpreadOf(values);
}

std::vector<const PartitionOutcome*> OfMethod(const std::vector<PartitionOutcome>& outcomes,
                                              const std::string& method) {
  std::vector<const PartitionOutcome*> selected;
  for (const PartitionOutcome& o : outcomes) {
    if (o.method == method) selected.push_back(&o);
  }
  return selected;
}

std::string Format(const char* format, double a, double b = 0.0) {
  char text[96];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

std::string MeanSd(const Spread& s) {
  if (s.n == 0) return "-";
  return Format("%.4g", s.mean) + (std::isfinite(s.sd) ? Format(" ± %.2g", s.sd) : "");
}

std::string Pad(const std::string& text, size_t width) {
  // The width counts characters; "±" takes two bytes.
  size_t length = 0;
  for (char ch : text) length += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  return text + std::string(width > length ? width - length : 1, ' ');
}

json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json SpreadToJson(const Spread& s) {
  return {{"n", s.n}, {"mean", Number(s.mean)}, {"sd", Number(s.sd)}};
}

json MetricsToJson(const std::vector<ChannelMetrics>& metrics) {
  json j = json::object();
  for (const ChannelMetrics& m : metrics) {
    j[m.output] = {{"samples", m.samples},
                   {"mae", Number(MetricValue(m, "mae"))},
                   {"rmse", Number(MetricValue(m, "rmse"))},
                   {"r2", Number(MetricValue(m, "r2"))}};
  }
  return j;
}

json OutcomeToJson(const StudyResult& result, const PartitionOutcome& o) {
  json j = {{"method", o.method},
            {"seed", o.seed},
            {"training_share", o.training_share},
            {"usable", o.usable},
            {"message", o.message},
            {"training",
             {{"records", o.training_records},
              {"samples", o.training_samples},
              {"one_step", MetricsToJson(o.training)}}},
            {"validation",
             {{"records", o.validation_records},
              {"samples", o.validation_samples},
              {"one_step", MetricsToJson(o.validation)}}},
            {"time_seconds", o.time_seconds}};
  if (o.method == "segments") j["validation"]["free_run"] = MetricsToJson(o.free_run);
  j["validation"]["persistence"] = MetricsToJson(o.persistence);
  json parameters = json::object();
  for (size_t i = 0; i < o.parameters.size(); ++i) {
    parameters[result.parameters[i]] = Number(o.parameters[i]);
  }
  j["parameters"] = parameters;
  return j;
}

}  // namespace

bool StudyOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    *error = what;
    return false;
  };
  if (partitions < 1) return fail("partitions must be >= 1");
  if (!(validation_share > 0.0 && validation_share < 1.0)) {
    return fail("validation_share must be in (0, 1)");
  }
  for (double share : training_shares) {
    if (!(share > 0.0 && validation_share + share <= 1.0 + 1e-9)) {
      return fail("each training share must be > 0 with validation_share + share <= 1");
    }
  }
  if (methods.empty()) return fail("no partition method (segments, points)");
  for (const std::string& method : methods) {
    if (method != "segments" && method != "points") {
      return fail("unknown partition method '" + method + "' (segments, points)");
    }
  }
  return true;
}

std::vector<ParameterSpec> StudyParameterSpecs(const StageConfig& stage, const ModelInfo& info) {
  std::vector<ParameterSpec> specs;
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    ParameterSpec spec;
    spec.name = info.parameters[i];
    spec.role = ParameterRole::kFixed;
    spec.start = info.parameter_defaults[i];
    for (const ParameterSpec& s : stage.parameters) {
      if (s.name == spec.name) spec = s;
    }
    if (spec.start_from_previous) {
      spec.start = info.parameter_defaults[i];
      spec.start_from_previous = false;
    }
    specs.push_back(spec);
  }
  return specs;
}

bool RunPartitionStudy(const RunConfig& config, const StudyOptions& options, StudyResult* result,
                       std::string* error, const StudyProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  auto fail = [&](const std::string& what) {
    *error = "study: " + what;
    return false;
  };
  StudyResult r;
  r.options = options;
  StudyOptions& o = r.options;
  if (!o.IsValid(error)) return fail(*error);
  StudyContext c;
  c.config = &config;
  for (const StageConfig& stage : config.stages) {
    const bool named = !o.stage.empty() && stage.options.name == o.stage;
    if (named && stage.kind != StageConfig::Kind::kLeastSquares) {
      return fail("stage '" + o.stage + "' is not a least_squares stage");
    }
    if (stage.kind == StageConfig::Kind::kLeastSquares && (named || o.stage.empty())) {
      c.stage = &stage;
      break;
    }
  }
  if (c.stage == nullptr) {
    return fail(o.stage.empty() ? "the run has no least_squares stage"
                                : "no stage named '" + o.stage + "'");
  }
  o.stage = c.stage->options.name;
  c.model = c.stage->model ? c.stage->model.get() : config.model.get();
  const ModelInfo& info = c.model->info();
  if (o.experiments.empty()) {
    for (const auto* list : {&c.stage->experiments, &c.stage->validation}) {
      for (const std::string& name : *list) {
        if (std::find(o.experiments.begin(), o.experiments.end(), name) == o.experiments.end()) {
          o.experiments.push_back(name);
        }
      }
    }
  }
  for (const std::string& name : o.experiments) {
    if (config.FindExperiment(name) == nullptr) return fail("no experiment named '" + name + "'");
  }
  c.specs = StudyParameterSpecs(*c.stage, info);
  for (const ParameterSpec& spec : c.specs) {
    if (spec.role != ParameterRole::kFixed && !spec.IsValid("stage '" + o.stage + "'", error)) {
      return fail(*error);
    }
  }
  if (!PrepareRegressionRecords(config, o.experiments, *c.model, c.stage->regression_data, &c.cache,
                                &c.pool, error)) {
    return fail(*error);
  }
  // A segment listed by two experiments of the pool (held-out segments and their copy with
  // reference outputs) is one record, the first.
  std::set<std::tuple<std::string, double, double>> seen;
  std::vector<RegressionRecord> unique;
  for (RegressionRecord& record : c.pool) {
    if (record.size() == 0) continue;
    const auto key = std::make_tuple(config.FindExperiment(record.record)->file, record.t.front(),
                                     record.t.back());
    if (seen.insert(key).second) {
      unique.push_back(std::move(record));
    } else {
      ++r.duplicates;
    }
  }
  // File and time order: a split by segments with seed s then holds out the segments an
  // experiment's `segments: {validation_share, seed: s}` holds out (RandomValidationMask).
  std::stable_sort(unique.begin(), unique.end(),
                   [&](const RegressionRecord& a, const RegressionRecord& b) {
                     const std::string& fa = config.FindExperiment(a.record)->file;
                     const std::string& fb = config.FindExperiment(b.record)->file;
                     return fa != fb ? fa < fb : a.t.front() < b.t.front();
                   });
  c.pool = std::move(unique);
  for (const RegressionRecord& record : c.pool) c.samples += CountUsed(record);
  if (c.pool.empty()) return fail("the pool has no records");

  r.model = info.name;
  r.records = static_cast<int>(c.pool.size());
  r.samples = c.samples;
  for (int s : c.model->regression_form()->states) r.states.push_back(info.states[s]);
  r.parameters = info.parameters;
  for (const ParameterSpec& spec : c.specs) r.held.push_back(spec.role == ParameterRole::kFixed);

  // (a) repeated splits, training all the rest.
  for (const std::string& method : o.methods) {
    for (int k = 0; k < o.partitions; ++k) {
      r.repeated.push_back(
          RunSplit(&c, method, o.seed + static_cast<unsigned>(k), o.validation_share, 0.0, true));
      if (progress) progress(ProgressLine(r.repeated.back(), "(a)"));
    }
  }
  // (b) one split per training share: the first repetition of (a) when the counts agree.
  for (double share : o.training_shares) {
    for (const std::string& method : o.methods) {
      const bool same = c.TrainingUnits(method, o.validation_share, share, false) ==
                        c.TrainingUnits(method, o.validation_share, share, true);
      const PartitionOutcome* first = nullptr;
      for (const PartitionOutcome& a : r.repeated) {
        if (a.method == method && a.seed == o.seed && first == nullptr) first = &a;
      }
      if (same && first != nullptr) {
        r.shares.push_back(*first);
        r.shares.back().training_share = share;
      } else {
        r.shares.push_back(RunSplit(&c, method, o.seed, o.validation_share, share, false));
        if (progress) progress(ProgressLine(r.shares.back(), "(b)"));
      }
    }
  }
  r.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(r);
  return true;
}

std::string StudyResultToText(const StudyResult& result) {
  const StudyOptions& o = result.options;
  std::ostringstream out;
  std::string pool;
  for (const std::string& name : o.experiments) pool += (pool.empty() ? "" : ", ") + name;
  out << "Partition study of stage '" << o.stage << "' (model " << result.model << ")\n"
      << "pool: " << pool << ": " << result.records << " records, " << result.samples
      << " samples; seed " << o.seed << "\n";
  if (result.duplicates > 0) {
    out << result.duplicates << " records listed twice in the pool (same file and window) "
        << "counted once\n";
  }
  out << "one-step: x(k+1) predicted from the data at k, each equation on its own regions;\n"
      << "free-run: held-out segments simulated whole; x(k+1)=x(k): one-step without a model\n";

  // (a)
  out << "\n(a) " << o.partitions << " random partitions, training "
      << Format("%.0f %%", 100.0 * (1.0 - o.validation_share)) << " / validation "
      << Format("%.0f %%", 100.0 * o.validation_share)
      << ": validation metrics, mean ± SD over the partitions\n";
  out << Pad("method", 10) << Pad("metric", 13) << Pad("n", 4);
  for (const char* metric : {"MAE", "R2"}) {
    for (const std::string& s : result.states) out << Pad(std::string(metric) + " " + s, 20);
  }
  out << "\n";
  std::vector<std::string> failures;
  for (const std::string& method : o.methods) {
    const auto outcomes = OfMethod(result.repeated, method);
    for (const std::string part : {"validation", "free_run", "persistence"}) {
      if (part == "free_run" && method != "segments") continue;
      const Spread count = MetricSpread(outcomes, part, result.states.front(), "r2");
      const std::string label = part == "validation" ? "one-step"
                                : part == "free_run" ? "free-run"
                                                     : "x(k+1)=x(k)";
      out << Pad(method, 10) << Pad(label, 13) << Pad(std::to_string(count.n), 4);
      for (const char* metric : {"mae", "r2"}) {
        for (const std::string& s : result.states) {
          out << Pad(MeanSd(MetricSpread(outcomes, part, s, metric)), 20);
        }
      }
      out << "\n";
    }
    for (const PartitionOutcome* a : outcomes) {
      if (!a->message.empty()) {
        failures.push_back("(a) " + method + " seed " + std::to_string(a->seed) + ": " +
                           a->message);
      }
    }
  }

  // (b)
  out << "\n(b) training share, validation " << Format("%.0f %%", 100.0 * o.validation_share)
      << " (seed " << o.seed << "): one-step metrics\n";
  out << Pad("share", 7) << Pad("method", 10) << Pad("part", 12) << Pad("n", 7);
  for (const char* metric : {"MAE", "R2"}) {
    for (const std::string& s : result.states) out << Pad(std::string(metric) + " " + s, 10);
  }
  out << "\n";
  for (const PartitionOutcome& b : result.shares) {
    for (const char* part : {"training", "validation"}) {
      out << Pad(Format("%.2f", b.training_share), 7) << Pad(b.method, 10) << Pad(part, 12);
      if (!b.usable) {
        out << "failed: " << b.message << "\n";
        break;
      }
      out << Pad(std::to_string(std::string(part) == "training" ? b.training_samples
                                                                : b.validation_samples),
                 7);
      for (const char* metric : {"mae", "r2"}) {
        for (const std::string& s : result.states) {
          double value = kNaN;
          for (const ChannelMetrics& m : Metrics(b, part)) {
            if (m.output == s) value = MetricValue(m, metric);
          }
          out << Pad(std::isfinite(value) ? Format("%.4g", value) : "-", 10);
        }
      }
      out << "\n";
    }
    if (!b.message.empty() && b.usable) {
      failures.push_back("(b) " + b.method + Format(" share %.2f: ", b.training_share) + b.message);
    }
  }
  out << "n: grid samples of the part; each equation is measured on those in its regions\n";

  // Parameter spread.
  out << "\nparameters over the partitions of (a): mean ± SD (SD relative to |mean|)\n";
  out << Pad("parameter", 12);
  for (const std::string& method : o.methods) out << Pad(method, 32);
  out << "\n";
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    out << Pad(result.parameters[i], 12);
    for (const std::string& method : o.methods) {
      const Spread s = ParameterSpread(OfMethod(result.repeated, method), i);
      std::string cell = result.held[i] ? Format("%.4g (held)", s.mean) : MeanSd(s);
      if (!result.held[i] && std::isfinite(s.sd)) {  // beyond 100 %: not even the sign
        const double relative = 100.0 * s.sd / std::abs(s.mean);
        cell += relative < 100.0 ? Format(" (%.1f %%)", relative) : " (>100 %)";
      }
      out << Pad(cell, 32);
    }
    out << "\n";
  }
  if (!failures.empty()) {
    out << "\nfailed or incomplete splits:\n";
    for (const std::string& f : failures) out << "  " << f << "\n";
  }
  out << Format("\ntime %.1f s\n", result.time_seconds);
  return out.str();
}

json StudyResultToJson(const StudyResult& result) {
  const StudyOptions& o = result.options;
  json j;
  j["stage"] = o.stage;
  j["model"] = result.model;
  j["options"] = {{"experiments", o.experiments},
                  {"partitions", o.partitions},
                  {"validation_share", o.validation_share},
                  {"training_shares", o.training_shares},
                  {"methods", o.methods},
                  {"seed", o.seed}};
  j["pool"] = {
      {"records", result.records}, {"samples", result.samples}, {"duplicates", result.duplicates}};
  j["states"] = result.states;
  json parameters = json::array();
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    parameters.push_back(
        {{"name", result.parameters[i]}, {"held", static_cast<bool>(result.held[i])}});
  }
  j["parameters"] = parameters;
  json repeated = json::object();
  for (const std::string& method : o.methods) {
    const auto outcomes = OfMethod(result.repeated, method);
    json m;
    json partitions = json::array();
    int failed = 0;
    for (const PartitionOutcome* a : outcomes) {
      partitions.push_back(OutcomeToJson(result, *a));
      failed += !a->usable;
    }
    m["partitions"] = partitions;
    m["failed"] = failed;
    json summary = json::object();
    for (const std::string part : {"training", "validation", "free_run", "persistence"}) {
      if (part == "free_run" && method != "segments") continue;
      json states = json::object();
      for (const std::string& s : result.states) {
        states[s] = {{"mae", SpreadToJson(MetricSpread(outcomes, part, s, "mae"))},
                     {"r2", SpreadToJson(MetricSpread(outcomes, part, s, "r2"))}};
      }
      const bool one_step = part == "training" || part == "validation";
      summary[one_step ? part + "_one_step" : part] = states;
    }
    json spread = json::object();
    for (size_t i = 0; i < result.parameters.size(); ++i) {
      spread[result.parameters[i]] = SpreadToJson(ParameterSpread(outcomes, i));
    }
    summary["parameters"] = spread;
    m["summary"] = summary;
    repeated[method] = m;
  }
  j["repeated"] = repeated;
  json shares = json::array();
  for (const PartitionOutcome& b : result.shares) shares.push_back(OutcomeToJson(result, b));
  j["shares"] = shares;
  j["time_seconds"] = result.time_seconds;
  return j;
}

}  // namespace vesselid
