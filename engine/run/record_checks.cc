#include "engine/run/record_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {
namespace {

constexpr double kGridShare = 0.95;       // gaps on the grid
constexpr double kDistinctShare = 0.2;    // distinct values per sample at most
constexpr double kMidManoeuvre = 0.4;     // |first sample| / largest |sample| of an angle input
constexpr size_t kFewestSamples = 20;     // shorter columns are not judged

bool IsDegrees(const ExperimentSpec& spec, const std::string& column) {
  return std::find(spec.degree_columns.begin(), spec.degree_columns.end(), column) !=
         spec.degree_columns.end();
}

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

}  // namespace

double QuantisationStep(const std::vector<double>& values) {
  if (values.size() < kFewestSamples) return 0.0;
  std::vector<double> distinct = values;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  if (distinct.size() < 3 || distinct.size() > kDistinctShare * values.size()) return 0.0;
  std::vector<double> gaps;
  for (size_t i = 1; i < distinct.size(); ++i) gaps.push_back(distinct[i] - distinct[i - 1]);
  const double q = *std::min_element(gaps.begin(), gaps.end());
  if (!(q > 0.0)) return 0.0;
  size_t on_grid = 0;
  for (double g : gaps) {
    const double multiple = g / q;
    on_grid += std::abs(multiple - std::round(multiple)) <= 1e-3 * multiple;
  }
  return on_grid >= kGridShare * gaps.size() ? q : 0.0;
}

void AddRecordCheckFindings(const RunConfig& config, TrajectoryCache* cache,
                            std::vector<Finding>* findings) {
  const ModelInfo& info = config.model->info();
  for (const ExperimentSpec& spec : config.experiments) {
    auto add = [&](FindingKind kind, const std::string& channel, double value,
                   const std::string& message) {
      Finding f = MakeFinding(kind, message);
      f.experiment = spec.name;
      f.output = channel;
      f.value = value;
      findings->push_back(std::move(f));
    };
    std::vector<std::pair<std::string, std::string>> channels;  // (model name, column)
    for (const auto& [input, column] : spec.inputs) channels.emplace_back(input, column);
    const size_t inputs = channels.size();
    for (const auto& [output, column] : spec.outputs) channels.emplace_back(output, column);
    for (size_t c = 0; c < channels.size(); ++c) {
      const auto& [name, column] = channels[c];
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values) || values.size() < kFewestSamples) continue;
      const bool degrees = IsDegrees(spec, column);
      const double unit = degrees ? 180.0 / M_PI : 1.0;
      const std::string label = degrees ? " deg" : "";
      const auto [low, high] = std::minmax_element(values.begin(), values.end());
      if (c < inputs && *low == 0.0 && *high == 0.0) {
        add(FindingKind::kAllZeroInput, name, 0.0,
            "column '" + column + "' is 0 in all " + std::to_string(values.size()) +
                " samples: what the input drives cannot be identified from this record");
        continue;
      }
      const double q = QuantisationStep(values);
      if (q > 0.0) {
        add(FindingKind::kQuantised, name, q * unit,
            "column '" + column + "' is quantised in steps of " + Number(q * unit) + label +
                ": its noise is at least " + Number(q * unit / std::sqrt(12.0)) + label);
      }
      const int input = info.InputIndex(name);
      if (c < inputs && input >= 0 && info.InputUnit(input) == "rad") {
        const double largest = std::max(std::abs(*low), std::abs(*high));
        const double share = std::abs(values.front()) / largest;
        if (share >= kMidManoeuvre) {
          add(FindingKind::kStartsMidManoeuvre, name, values.front() * unit,
              "column '" + column + "' starts at " + Number(values.front() * unit) + label +
                  ", " + Number(100.0 * share) + " % of its largest magnitude " +
                  Number(largest * unit) + label + ": the record starts mid-manoeuvre");
        }
      }
    }
  }
}

}  // namespace vesselid
