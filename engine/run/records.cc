#include "engine/run/records.h"

#include <algorithm>

#include "engine/data/segments.h"
#include "engine/model/input_range.h"

namespace vesselid {
namespace {

// Consecutive pieces of `length` of [begin, end] of `spec` named "<prefix><k>", k from 1; a
// remainder shorter than half the length is left out. A given initial state is the record's:
// pieces after the first start from the data.
void SplitByLength(const ExperimentSpec& spec, const std::string& prefix, double begin, double end,
                   double length, std::vector<ExperimentSpec>* specs) {
  int k = 1;
  for (double t0 = begin; t0 + 0.5 * length < end; t0 += length) {
    ExperimentSpec piece = spec;
    piece.name = prefix + std::to_string(k);
    piece.t_begin = t0;
    piece.t_end = std::min(end, t0 + length);
    if (k++ > 1) piece.initial_state.clear();
    specs->push_back(piece);
  }
}

// The record itself, its `segment` column's segments or consecutive pieces of a length; with
// `segment_length` > 0 (continuation) every segment is cut into pieces of that length too,
// "<name>@<id>.<k>".
bool WholeRecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                      std::vector<ExperimentSpec>* specs, std::string* error) {
  specs->clear();
  if (!spec.segments.column.empty()) {
    std::vector<SegmentRange> ranges;
    if (!SelectSegments(data, spec.segments, &ranges, error)) {
      *error = "experiment '" + spec.name + "': " + *error;
      return false;
    }
    for (const SegmentRange& range : ranges) {
      ExperimentSpec segment = spec;
      segment.name = spec.name + "@" + std::to_string(range.id);
      segment.t_begin = std::max(spec.t_begin, range.t_begin);
      segment.t_end = std::min(spec.t_end, range.t_end);
      if (!(segment.t_end > segment.t_begin)) continue;
      if (segment_length > 0.0) {
        SplitByLength(segment, segment.name + ".", segment.t_begin, segment.t_end, segment_length,
                      specs);
      } else {
        specs->push_back(segment);
      }
    }
    return true;
  }
  double length = spec.segment_length;
  if (segment_length > 0.0)
    length = length > 0.0 ? std::min(length, segment_length) : segment_length;
  if (length <= 0.0) {
    specs->push_back(spec);
    return true;
  }
  const double begin = std::max(spec.t_begin, data.t.front());
  const double end = std::min(spec.t_end, data.t.back());
  SplitByLength(spec, spec.name + "@", begin, end, length, specs);
  return true;
}

// Calls `build` with every experiment spec the records `names` are cut into, and its data.
template <class Build>
bool ForEachRecordSpec(const RunConfig& config, const std::vector<std::string>& names,
                       double segment_length, TrajectoryCache* cache, const Build& build,
                       std::string* error) {
  for (const std::string& name : names) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    const Trajectory* data = LoadCachedTrajectory(*spec, cache, error);
    std::vector<ExperimentSpec> specs;
    if (data == nullptr || !RecordSpecs(*spec, *data, segment_length, &specs, error)) return false;
    for (const ExperimentSpec& s : specs) {
      if (!build(name, s, *data)) return false;
    }
  }
  return true;
}

}  // namespace

const Trajectory* LoadCachedTrajectory(const ExperimentSpec& spec, TrajectoryCache* cache,
                                       std::string* error) {
  auto cached = cache->find(spec.name);
  if (cached == cache->end()) {
    Trajectory trajectory;
    if (!LoadExperimentData(spec, &trajectory, error)) return nullptr;
    cached = cache->emplace(spec.name, std::move(trajectory)).first;
  }
  return &cached->second;
}

bool RecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                 std::vector<ExperimentSpec>* specs, std::string* error) {
  std::vector<ExperimentSpec> whole;
  if (!WholeRecordSpecs(spec, data, segment_length, &whole, error)) return false;
  specs->clear();
  for (const ExperimentSpec& s : whole) {
    if (!SplitByInputRange(s, data, specs, error)) return false;
  }
  return true;
}

bool PrepareExperiments(const RunConfig& config, const std::vector<std::string>& names,
                        const ModelHandle& model, const ExperimentOptions& stage_options,
                        TrajectoryCache* cache, std::vector<Experiment>* experiments,
                        std::string* error, double segment_length) {
  const ModelInfo& info = model.info();
  ExperimentOptions options = stage_options;
  options.state_guess = [&model](const double* y, const double* ydot, double* x) {
    model.GuessState(y, ydot, x);
  };
  experiments->clear();
  return ForEachRecordSpec(
      config, names, segment_length, cache,
      [&](const std::string& name, const ExperimentSpec& s, const Trajectory& data) {
        Experiment experiment;
        if (!BuildExperiment(s, data, info, options, &experiment, error)) return false;
        experiment.record = name;
        experiment.segment = s.name != name;
        experiments->push_back(std::move(experiment));
        return true;
      },
      error);
}

bool PrepareRegressionRecords(const RunConfig& config, const std::vector<std::string>& names,
                              const ModelHandle& model, const RegressionDataOptions& options,
                              TrajectoryCache* cache, std::vector<RegressionRecord>* records,
                              std::string* error) {
  records->clear();
  return ForEachRecordSpec(
      config, names, 0.0, cache,
      [&](const std::string& name, const ExperimentSpec& s, const Trajectory& data) {
        RegressionRecord record;
        if (!BuildRegressionRecord(s, data, model, options, &record, error)) return false;
        record.record = name;
        records->push_back(std::move(record));
        return true;
      },
      error);
}

}  // namespace vesselid
