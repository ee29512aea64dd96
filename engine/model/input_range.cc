#include "engine/model/input_range.h"

#include <cmath>

namespace vesselid {

bool SplitByInputRange(const ExperimentSpec& spec, const Trajectory& data,
                       std::vector<ExperimentSpec>* pieces, std::string* error) {
  if (spec.input_range.empty()) {
    pieces->push_back(spec);
    return true;
  }
  struct Ranged {
    int column;
    double lower, upper;
  };
  std::vector<Ranged> ranged;
  for (const auto& [input, range] : spec.input_range) {
    auto mapped = spec.inputs.find(input);
    const int column = mapped == spec.inputs.end() ? -1 : data.Find(mapped->second);
    if (column < 0) {
      *error = "experiment '" + spec.name + "': input_range names input '" + input +
               "', which is not mapped to a column of " + data.source;
      return false;
    }
    ranged.push_back({column, range.first, range.second});
  }
  std::vector<double> last(ranged.size(), std::nan(""));
  int k = 1;
  double begin = std::nan("");  // start of the current stretch
  double previous = 0.0;        // last row inside it
  bool after_outside = false;  // the current stretch follows rows outside the ranges
  auto close = [&]() {
    if (std::isfinite(begin) && after_outside) begin += spec.input_range_skip;
    if (std::isfinite(begin) && previous - begin >= spec.input_range_min_duration &&
        previous > begin) {
      ExperimentSpec piece = spec;
      piece.name = spec.name + "#" + std::to_string(k++);
      piece.t_begin = begin;
      piece.t_end = previous;
      piece.input_range.clear();
      pieces->push_back(piece);
    }
    begin = std::nan("");
  };
  for (size_t row = 0; row < data.t.size(); ++row) {
    const double t = data.t[row];
    if (t < spec.t_begin || t > spec.t_end) continue;
    bool inside = true;
    for (size_t i = 0; i < ranged.size(); ++i) {
      const double v = data.columns[ranged[i].column][row];
      if (std::isfinite(v)) last[i] = v;
      inside = inside && std::isfinite(last[i]) && last[i] >= ranged[i].lower &&
               last[i] <= ranged[i].upper;
    }
    if (inside) {
      if (!std::isfinite(begin)) begin = t;
      previous = t;
    } else {
      close();
      after_outside = true;
    }
  }
  close();
  return true;
}

}  // namespace vesselid
