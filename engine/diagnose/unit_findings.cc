#include "engine/diagnose/unit_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/base/statistics.h"
#include "engine/data/angle_units.h"

namespace vesselid {
namespace {

// An angle input beyond any rudder: the largest magnitude, and what it is in degrees.
void AddAngleInputFinding(const ExperimentSpec& spec, const std::string& input,
                          const std::string& column, const std::vector<double>& values,
                          std::vector<Finding>* findings) {
  double largest = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }
  if (!(largest > kMaxAngleInput)) return;
  char text[320];
  std::snprintf(text, sizeof(text),
                "input column '%s' reaches %.4g rad (%.4g deg), beyond any rudder or fin (%.0f "
                "deg): it looks like degrees read as radians; add it to degrees:",
                column.c_str(), largest, largest * 180.0 / M_PI, kMaxAngleInput * 180.0 / M_PI);
  Finding f = MakeFinding(FindingKind::kUnitSuspect, text);
  f.experiment = spec.name;
  f.input = input;
  f.value = largest;
  f.threshold = kMaxAngleInput;
  findings->push_back(std::move(f));
}

// A record whose median sample interval is beyond what a ship's motion is logged at.
void AddSampleIntervalFinding(const ExperimentSpec& spec, const Trajectory& data,
                              std::vector<Finding>* findings) {
  std::vector<double> steps;
  for (size_t k = 1; k < data.t.size(); ++k) {
    if (data.t[k] >= spec.t_begin && data.t[k] <= spec.t_end) steps.push_back(data.t[k] - data.t[k - 1]);
  }
  if (steps.empty()) return;
  const double median = UpperMedian(std::move(steps));
  char text[320];
  if (median > kMaxSampleInterval) {
    std::snprintf(text, sizeof(text),
                  "the time column's median sample interval is %.4g s: a ship's motion is "
                  "logged at 0.01-%.0f s; it looks like milliseconds read as seconds (%.4g s): "
                  "give time: {unit: ms}",
                  median, kMaxSampleInterval, median / 1000.0);
  } else if (median > 0.0 && median < kMinSampleInterval) {
    std::snprintf(text, sizeof(text),
                  "the time column's median sample interval is %.4g s: a ship's motion is "
                  "logged at 0.01-%.0f s; the time's unit looks wrong (seconds read as "
                  "milliseconds would give %.4g s): check time: {unit: ...}",
                  median, kMaxSampleInterval, median * 1000.0);
  } else {
    return;
  }
  Finding f = MakeFinding(FindingKind::kUnitSuspect, text);
  f.experiment = spec.name;
  f.value = median;
  f.threshold = median > kMaxSampleInterval ? kMaxSampleInterval : kMinSampleInterval;
  findings->push_back(std::move(f));
}

}  // namespace

void AddUnitFindings(const RunConfig& config, TrajectoryCache* cache,
                     std::vector<Finding>* findings) {
  const ModelInfo& info = config.model->info();
  for (const ExperimentSpec& spec : config.experiments) {
    for (const auto& [output, column] : spec.outputs) {
      const int o = info.OutputIndex(output);
      if (o < 0 || o >= static_cast<int>(info.angle_outputs.size()) || !info.angle_outputs[o]) {
        continue;
      }
      if (spec.IsDegreeColumn(column)) continue;
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values)) continue;
      const AngleUnitCheck check = CheckAngleUnit(values);
      if (check.looks_like_degrees) {
        Finding f = MakeFinding(FindingKind::kUnitSuspect, DescribeDegreesLook(column, check));
        f.experiment = spec.name;
        f.output = output;
        findings->push_back(std::move(f));
      }
    }
    for (const auto& [input, column] : spec.inputs) {
      const int i = info.InputIndex(input);
      if (i < 0 || info.InputUnit(i) != "rad" || spec.IsDegreeColumn(column)) continue;
      std::vector<double> values;
      if (WindowSamples(spec, column, cache, &values))
        AddAngleInputFinding(spec, input, column, values, findings);
    }
    std::string error;
    if (const Trajectory* data = cache->Load(spec, &error))
      AddSampleIntervalFinding(spec, *data, findings);
  }
}

}  // namespace vesselid
