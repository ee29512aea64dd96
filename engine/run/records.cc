#include "engine/run/records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

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

// The rows of `data` inside [begin, end] (its times increase): [first, last).
std::pair<size_t, size_t> RowsIn(const Trajectory& data, double begin, double end) {
  const auto first = std::lower_bound(data.t.begin(), data.t.end(), begin - 1e-9);
  const auto last = std::upper_bound(first, data.t.end(), end + 1e-9);
  return {static_cast<size_t>(first - data.t.begin()), static_cast<size_t>(last - data.t.begin())};
}

// Rows of `data` inside the window of `s` where the column `column` has a sample.
int SamplesInWindow(const Trajectory& data, const ExperimentSpec& s, const std::string& column) {
  const int c = data.Find(column);
  if (c < 0) return -1;
  const auto [first, last] = RowsIn(data, s.t_begin, s.t_end);
  int count = 0;
  for (size_t k = first; k < last; ++k) count += !std::isnan(data.columns[c][k]);
  return count;
}

// Rows inside the window of `s` where any of the columns of `outputs` has a sample.
int SampleTimes(const Trajectory& data, const ExperimentSpec& s,
                const std::vector<std::string>& outputs) {
  std::vector<int> columns;
  for (const std::string& output : outputs) {
    const auto mapped = s.outputs.find(output);
    if (mapped != s.outputs.end() && data.Find(mapped->second) >= 0) {
      columns.push_back(data.Find(mapped->second));
    }
  }
  const auto [first, last] = RowsIn(data, s.t_begin, s.t_end);
  int count = 0;
  for (size_t k = first; k < last; ++k) {
    for (int c : columns) {
      if (std::isnan(data.columns[c][k])) continue;
      ++count;
      break;
    }
  }
  return count;
}

// Records the note that a piece of a record was skipped, once per run (the record's
// preparation findings travel to the run's, record_notes.h).
void NoteSkipped(TrajectoryCache* cache, const std::string& record, const ExperimentSpec& piece,
                 const Trajectory& data, const std::string& why) {
  char span[96];
  std::snprintf(span, sizeof(span), " (t = %g to %g s)", std::max(piece.t_begin, data.t.front()),
                std::min(piece.t_end, data.t.back()));
  Finding skipped = MakeFinding(FindingKind::kSegmentSkipped, std::string("skipped") + span +
                                                                   ": " + why);
  skipped.experiment = record;
  skipped.segment = piece.name;
  skipped.value = std::min(piece.t_end, data.t.back()) - std::max(piece.t_begin, data.t.front());
  cache->AddNote(record, std::move(skipped));
}

// Calls `build` with every experiment spec the records `names` are cut into, and its data.
// A piece of a record (segment, length or input range) that `too_short` finds too short for
// the stage (a reason, or empty) is skipped with a note; a record left without pieces is an
// error.
// `split` may cut each piece further (into the specs it appends, or an error).
template <class Split, class TooShort, class Build>
bool ForEachRecordSpec(const RunConfig& config, const std::vector<std::string>& names,
                       double segment_length, TrajectoryCache* cache, const Split& split,
                       const TooShort& too_short, const Build& build, std::string* error) {
  for (const std::string& name : names) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    if (spec == nullptr) {  // the config reader checks the names a config gives
      *error = "no experiment '" + name + "' in the config";
      return false;
    }
    const Trajectory* data = LoadCachedTrajectory(*spec, cache, error);
    std::vector<ExperimentSpec> pieces, specs;
    if (data == nullptr || !RecordSpecs(*spec, *data, segment_length, &pieces, error)) return false;
    for (const ExperimentSpec& piece : pieces) {
      if (!split(name, piece, *data, &specs, error)) return false;
    }
    int built = 0;
    std::string last_reason;
    for (const ExperimentSpec& s : specs) {
      const std::string reason = s.name != name ? too_short(s, *data) : std::string();
      if (!reason.empty()) {
        NoteSkipped(cache, name, s, *data, reason);
        last_reason = reason;
        continue;
      }
      if (!build(name, s, *data)) return false;
      ++built;
    }
    if (built == 0 && !specs.empty() && !last_reason.empty()) {
      *error = "experiment '" + name + "' (" + spec->file + "): every one of its " +
               std::to_string(specs.size()) + " segment(s) is too short for the stage, e.g. " +
               last_reason;
      return false;
    }
  }
  return true;
}

}  // namespace

bool WindowSamples(const ExperimentSpec& spec, const std::string& column, TrajectoryCache* cache,
                   std::vector<double>* values) {
  std::string error;
  const Trajectory* data = LoadCachedTrajectory(spec, cache, &error);
  if (data == nullptr) return false;
  const int c = data->Find(column);
  if (c < 0) return false;
  values->clear();
  const auto first = std::lower_bound(data->t.begin(), data->t.end(), spec.t_begin);
  const auto last = std::upper_bound(first, data->t.end(), spec.t_end);
  for (size_t k = first - data->t.begin(); k < static_cast<size_t>(last - data->t.begin()); ++k) {
    const double v = data->columns[c][k];
    if (std::isfinite(v)) values->push_back(v);
  }
  return true;
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
  // A piece with fewer sample times than the model has states cannot tell its own initial
  // state from the parameters.
  const auto too_short = [&](const ExperimentSpec& s, const Trajectory& data) {
    std::vector<std::string> outputs = options.outputs;
    if (outputs.empty()) {
      for (const auto& [output, column] : s.outputs) outputs.push_back(output);
    }
    const int times = SampleTimes(data, s, outputs);
    if (times >= static_cast<int>(info.states.size()) && times >= 2) return std::string();
    return std::to_string(times) + " sample time(s) of its outputs, fewer than the " +
           std::to_string(std::max<size_t>(2, info.states.size())) + " the model's states need";
  };
  const auto whole = [](const std::string&, const ExperimentSpec& s, const Trajectory&,
                        std::vector<ExperimentSpec>* specs, std::string*) {
    specs->push_back(s);
    return true;
  };
  std::map<const Trajectory*, RecordChannels> record_channels;  // for the record's segments
  return ForEachRecordSpec(
      config, names, segment_length, cache, whole, too_short,
      [&](const std::string& name, const ExperimentSpec& s, const Trajectory& data) {
        Experiment experiment;
        RecordChannels& channels = record_channels.try_emplace(&data, data).first->second;
        if (!BuildExperiment(s, &channels, info, options, &experiment, error)) return false;
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
  // The grid output of a piece: the given one, else the sparsest mapped output.
  const auto grid_of = [&](const ExperimentSpec& s, const Trajectory& data, std::string* output) {
    int fewest = -1;
    for (const auto& [name, column] : s.outputs) {
      if (!options.grid_output.empty() && name != options.grid_output) continue;
      const int count = SamplesInWindow(data, s, column);
      if (count >= 0 && (fewest < 0 || count < fewest)) {
        fewest = count;
        *output = name;
      }
    }
    return fewest;
  };
  // A gap of missing grid samples (GridStepOf: kGap) cuts a piece in two, "<piece>~<k>", with a
  // finding; a step only irregular (row jitter) stays BuildRegressionRecord's error unless
  // max_gap admits it.
  const auto split = [&](const std::string& record, const ExperimentSpec& s, const Trajectory& data,
                         std::vector<ExperimentSpec>* specs, std::string*) {
    std::string output;
    if (grid_of(s, data, &output) < 3) {
      specs->push_back(s);
      return true;
    }
    const int column = data.Find(s.outputs.at(output));
    std::vector<double> t;
    for (size_t k = 0; k < data.t.size(); ++k) {
      if (data.t[k] >= s.t_begin - 1e-9 && data.t[k] <= s.t_end + 1e-9 &&
          !std::isnan(data.columns[column][k])) {
        t.push_back(data.t[k]);
      }
    }
    std::vector<double> steps;
    for (size_t k = 1; k < t.size(); ++k) steps.push_back(t[k] - t[k - 1]);
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double limit = std::max(options.max_gap, kMissingSampleStep) * median;
    std::vector<size_t> cuts;
    for (size_t k = 0; k < steps.size(); ++k) {
      if (GridStepOf(steps[k], median, options.max_gap) == GridStep::kGap) cuts.push_back(k);
    }
    if (cuts.empty()) {
      specs->push_back(s);
      return true;
    }
    std::string where;
    double begin = t.front();
    cuts.push_back(steps.size());
    for (size_t i = 0; i < cuts.size(); ++i) {
      ExperimentSpec part = s;
      part.name = s.name + "~" + std::to_string(i + 1);
      part.t_begin = begin;
      part.t_end = t[cuts[i]];
      if (i > 0) part.initial_state.clear();
      specs->push_back(part);
      if (cuts[i] < steps.size()) {
        char text[96];
        std::snprintf(text, sizeof(text), "%s%.3g s at t = %g s", where.empty() ? "" : ", ",
                      steps[cuts[i]], t[cuts[i]]);
        where += text;
        begin = t[cuts[i] + 1];
      }
    }
    char text[200];
    std::snprintf(text, sizeof(text),
                  "' cut into %zu pieces at gaps of its output %s longer than %g median steps "
                  "(equation-error grid; max_gap): ",
                  cuts.size(), output.c_str(), limit / sorted[sorted.size() / 2]);
    Finding cut = MakeFinding(FindingKind::kRecordCut, "'" + s.name + text + where);
    cut.experiment = record;
    cut.value = static_cast<double>(cuts.size());  // pieces
    cache->AddNote(record, std::move(cut));
    return true;
  };
  // The Savitzky-Golay window must fit in the samples of the grid output.
  const auto too_short = [&](const ExperimentSpec& s, const Trajectory& data) {
    std::string grid;
    const int fewest = grid_of(s, data, &grid);
    const int window = 2 * options.smoothing.half_width + 1;
    if (fewest < 0 || fewest >= window) return std::string();
    return "Savitzky-Golay window of " + std::to_string(window) + " samples is longer than the " +
           std::to_string(fewest) + " samples of its output " + grid +
           " (the stage's smoothing.half_width)";
  };
  return ForEachRecordSpec(
      config, names, 0.0, cache, split, too_short,
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
