// Section readers shared by config.cc, study_config.cc and step_regression_config.cc.
#include "engine/config/config_sections.h"

#include <limits>

namespace vesselid {

namespace {

// `horizons: auto | none | [lengths]` of a stage's global start.
void ReadHorizons(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                  SearchHorizons* horizons) {
  if (node.IsScalar()) {
    const std::string text = reader.String(node, key);
    if (text == "auto") {
      horizons->mode = SearchHorizons::Mode::kAuto;
    } else if (text == "none") {
      horizons->mode = SearchHorizons::Mode::kNone;
    } else {
      reader.Fail(node, key, "auto, none or a list of segment lengths in s, not '" + text + "'");
    }
    return;
  }
  horizons->mode = SearchHorizons::Mode::kGiven;
  horizons->lengths = ReadSegmentLengths(reader, node, key);
  if (horizons->lengths.empty()) reader.Fail(node, key, "at least one segment length (or none)");
}

}  // namespace

std::vector<double> ReadSegmentLengths(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& key) {
  std::vector<double> lengths = reader.Doubles(node, key);
  for (size_t i = 0; i < lengths.size(); ++i) {
    const bool increasing = i == 0 || lengths[i] > lengths[i - 1];
    if (!(lengths[i] > 0.0) || !increasing) {
      reader.Fail(node[i], Child(key, i), "segment lengths must be > 0 and increasing");
    }
  }
  return lengths;
}

void ReadGlobal(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                GlobalStartOptions* global, SearchHorizons* horizons) {
  reader.CheckMap(node, path,
                  {"algorithm", "points", "short_iterations", "threads", "max_evaluations",
                   "max_time", "seed", "population", "candidates", "min_separation",
                   "horizons"});
  reader.Read(node, path, "algorithm", &global->algorithm);
  reader.Read(node, path, "points", &global->points);
  reader.CheckLimit(node["points"], Child(path, "points"), global->points,
                    reader.limits().evaluations, "limits.evaluations");
  reader.Read(node, path, "short_iterations", &global->short_iterations);
  reader.Read(node, path, "threads", &global->threads);
  reader.Read(node, path, "max_evaluations", &global->max_evaluations);
  reader.CheckLimit(node["max_evaluations"], Child(path, "max_evaluations"),
                    global->max_evaluations, reader.limits().evaluations, "limits.evaluations");
  reader.Read(node, path, "max_time", &global->max_time_seconds);
  int seed = static_cast<int>(global->seed);
  reader.Read(node, path, "seed", &seed);
  global->seed = static_cast<unsigned>(seed);
  reader.Read(node, path, "population", &global->population);
  reader.Read(node, path, "candidates", &global->candidates);
  reader.Read(node, path, "min_separation", &global->min_separation);
  // Keys of the other kind of search would have no effect.
  const bool multistart = global->algorithm == "multistart";
  for (const char* key : {"max_evaluations", "population"}) {
    if (multistart && node[key]) {
      reader.Fail(node[key], Child(path, key),
                  std::string(key) + " applies to NLopt algorithms; the multistart takes points "
                                     "and short_iterations");
    }
  }
  if (const YAML::Node h = node["horizons"]) {
    if (horizons == nullptr) {
      reader.Fail(h, Child(path, "horizons"), "horizons applies to a stage's global start");
    }
    ReadHorizons(reader, h, Child(path, "horizons"), horizons);
  }
  for (const char* key : {"points", "short_iterations", "threads", "horizons"}) {
    if (!multistart && node[key]) {
      reader.Fail(node[key], Child(path, key),
                  std::string(key) + " applies to the multistart, not to NLopt's " +
                      global->algorithm + " (which takes max_evaluations)");
    }
  }
  std::string error;
  if (!global->IsValid(&error)) reader.Fail(node, path, error);
}

void CheckNames(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                const std::vector<std::string>& names, const std::vector<std::string>& known,
                const std::string& kind, const ModelInfo& info) {
  for (const std::string& name : names) {
    bool found = false;
    for (const std::string& k : known) found = found || k == name;
    if (!found) {
      reader.Fail(node, key,
                  "unknown " + kind + " '" + name + "' (model " + info.name + " has " +
                      JoinNames(known) + ")");
    }
  }
}

void ReadRegressionData(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                        const ModelInfo& info, RegressionDataOptions* data) {
  reader.Read(node, path, "max_gap", &data->max_gap);
  if (!(data->max_gap >= 1.0)) {
    reader.Fail(node["max_gap"], Child(path, "max_gap"), "must be >= 1 (median grid intervals)");
  }
  if (node["grid"]) {
    data->grid_output = reader.String(node["grid"], Child(path, "grid"));
    CheckNames(reader, node["grid"], Child(path, "grid"),
               std::vector<std::string>{data->grid_output}, info.outputs, "output", info);
  }
  if (const YAML::Node smoothing = node["smoothing"]) {
    const std::string key = Child(path, "smoothing");
    reader.CheckMap(smoothing, key, {"half_width", "order"});
    reader.Read(smoothing, key, "half_width", &data->smoothing.half_width);
    reader.Read(smoothing, key, "order", &data->smoothing.order);
    // The window, 2 half_width + 1 samples, must fit an int here and in SavitzkyGolay.
    constexpr int kMaxHalfWidth = (std::numeric_limits<int>::max() - 1) / 2;
    if (data->smoothing.half_width > kMaxHalfWidth) {
      reader.Fail(smoothing["half_width"], Child(key, "half_width"),
                  "must be <= " + std::to_string(kMaxHalfWidth));
    }
    if (data->smoothing.half_width < 1 || data->smoothing.order < 1 ||
        data->smoothing.order >= 2 * data->smoothing.half_width + 1) {
      reader.Fail(smoothing, key, "need half_width >= 1 and 1 <= order < 2 half_width + 1");
    }
  }
}

}  // namespace vesselid
