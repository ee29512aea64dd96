// The partition study's options, the split draw and the driver: the splits of tables (a)
// and (b) as cases of RunCases, merged on rank 0. The stage-specific pools are in
// partition_study_least_squares.cc and partition_study_output_error.cc, the tables in
// partition_study_report.cc.
#include "engine/study/partition_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "engine/run/run_config.h"

namespace vesselid {

using nlohmann::json;
using partition_internal::PartitionPool;
using partition_internal::SplitPart;

namespace partition_internal {

// Fisher-Yates with our own draws, as RandomValidationMask: std::shuffle's sequence is
// library-specific.
std::vector<SplitPart> DrawSplit(int count, double validation_share, int training,
                                 unsigned seed) {
  std::vector<int> order(count);
  for (int i = 0; i < count; ++i) order[i] = i;
  std::mt19937 random(seed);
  for (int i = count - 1; i > 0; --i) {
    std::swap(order[i], order[random() % static_cast<unsigned>(i + 1)]);
  }
  const int nv = std::min(count, static_cast<int>(std::lround(validation_share * count)));
  const int nt = std::min(count - nv, training);
  std::vector<SplitPart> parts(count, SplitPart::kUnused);
  for (int i = 0; i < nv + nt; ++i) {
    parts[order[i]] = i < nv ? SplitPart::kValidation : SplitPart::kTraining;
  }
  return parts;
}

}  // namespace partition_internal

namespace {

// One split to run: table (a) trains on all the rest, table (b) on round(share * units).
struct SplitCase {
  std::string method;
  unsigned seed = 0;
  double training_share = 0.0;
  bool rest = false;
};

// Training units of a split.
int TrainingUnits(const PartitionPool& pool, const StudyOptions& o, const std::string& method,
                  double share, bool rest) {
  const int units = pool.Units(method);
  const int nv = static_cast<int>(std::lround(o.validation_share * units));
  return rest ? units - nv : static_cast<int>(std::lround(share * units));
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

const StageConfig* PartitionStudyStage(const RunConfig& config, const std::string& name) {
  if (!name.empty()) {
    for (const StageConfig& stage : config.stages) {
      if (stage.options.name == name) return &stage;
    }
    return nullptr;
  }
  if (config.stages.empty()) return nullptr;
  if (config.stages.back().kind == StageConfig::Kind::kOutputError) return &config.stages.back();
  for (const StageConfig& stage : config.stages) {
    if (stage.kind == StageConfig::Kind::kLeastSquares) return &stage;
  }
  return nullptr;
}

bool RunPartitionStudy(const RunConfig& config, const StudyOptions& options,
                       const CaseOptions& execution, StudyResult* result, std::string* error,
                       const CaseProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  auto fail = [&](const std::string& what) {
    *error = "study: " + what;
    return false;
  };
  StudyResult r;
  r.options = options;
  const StudyOptions& o = r.options;
  if (!o.IsValid(error)) return fail(*error);
  const StageConfig* stage = PartitionStudyStage(config, o.stage);
  if (stage == nullptr) {
    return fail(o.stage.empty() ? "the run has no stage to study"
                                : "no stage named '" + o.stage + "'");
  }
  if (stage->kind == StageConfig::Kind::kStepRegression) {
    return fail("stage '" + stage->options.name +
                "': partition studies refit least-squares or output-error stages only");
  }
  r.options.stage = stage->options.name;
  const std::unique_ptr<PartitionPool> pool =
      stage->kind == StageConfig::Kind::kLeastSquares
          ? partition_internal::LeastSquaresPool(config, *stage, &r, error)
          : partition_internal::OutputErrorPool(config, *stage, &r, error);
  if (pool == nullptr) return fail(*error);

  // (a) repeated splits, training all the rest; (b) one split per training share, the first
  // repetition of (a) when the counts agree. reused[k]: case of (b)'s k-th split.
  std::vector<SplitCase> cases;
  for (const std::string& method : o.methods) {
    for (int k = 0; k < o.partitions; ++k) {
      cases.push_back({method, o.seed + static_cast<unsigned>(k), 1.0 - o.validation_share, true});
    }
  }
  const size_t repeated = cases.size();
  std::vector<size_t> share_case;
  for (double share : o.training_shares) {
    for (size_t m = 0; m < o.methods.size(); ++m) {
      const std::string& method = o.methods[m];
      if (TrainingUnits(*pool, o, method, share, false) ==
          TrainingUnits(*pool, o, method, share, true)) {
        share_case.push_back(m * o.partitions);
      } else {
        share_case.push_back(cases.size());
        cases.push_back({method, o.seed, share, false});
      }
    }
  }
  auto run_case = [&](int index) -> json {
    const auto case_start = std::chrono::steady_clock::now();
    const SplitCase& c = cases[index];
    const std::vector<SplitPart> parts = partition_internal::DrawSplit(
        pool->Units(c.method), o.validation_share,
        TrainingUnits(*pool, o, c.method, c.training_share, c.rest), c.seed);
    PartitionOutcome outcome = pool->Fit(c.method, parts);
    outcome.method = c.method;
    outcome.seed = c.seed;
    outcome.training_share = c.training_share;
    outcome.time_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - case_start).count();
    return partition_internal::OutcomeToJson(r, outcome);
  };
  std::vector<json> merged;
  RunCases(static_cast<int>(cases.size()), run_case, execution, &merged, progress);
  if (!ProcessGroup::Current().root()) {
    *result = StudyResult();
    return true;
  }
  std::vector<PartitionOutcome> outcomes;
  for (size_t i = 0; i < cases.size(); ++i) {
    PartitionOutcome outcome = partition_internal::OutcomeFromJson(r, merged[i]);
    outcome.method = cases[i].method;  // also for a case that threw
    outcome.seed = cases[i].seed;
    outcome.training_share = cases[i].training_share;
    outcomes.push_back(std::move(outcome));
  }
  r.repeated.assign(outcomes.begin(), outcomes.begin() + repeated);
  size_t k = 0;
  for (double share : o.training_shares) {
    for (size_t m = 0; m < o.methods.size(); ++m, ++k) {
      r.shares.push_back(outcomes[share_case[k]]);
      r.shares.back().training_share = share;
    }
  }
  r.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(r);
  return true;
}

}  // namespace vesselid
