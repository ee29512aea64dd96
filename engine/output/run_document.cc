#include "engine/output/run_document.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <algorithm>
#include <fstream>

#include "engine/base/json_number.h"
#include "engine/base/memory_budget.h"
#include "engine/output/output_folder.h"
#include "engine/output/output_staging.h"
#include "engine/output/stage_interpolation.h"
#include "engine/output/zigzag_report.h"
#include "engine/run/display_units.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// More than a run's results.json can be: its traces are CSV files beside it.
constexpr std::uintmax_t kMaxResultsBytes = 256ull << 20;

// A text member of `j`; "" where it is missing or no text (results.json writes null for what
// it does not know).
std::string Text(const json& j, const char* key) {
  const auto found = j.find(key);
  return found != j.end() && found->is_string() ? found->get<std::string>() : std::string();
}

// The state of an estimated start "x0.<state>[<experiment>]", once.
void AddFreeState(std::string name, RunDocument* d) {
  if (name.rfind("x0.", 0) == 0) name = name.substr(3);
  name = name.substr(0, name.find('['));
  if (std::find(d->free_initial_states.begin(), d->free_initial_states.end(), name) ==
      d->free_initial_states.end()) {
    d->free_initial_states.push_back(name);
  }
}

// The last output-error stage (one with estimates and a model): the model the final values
// were estimated with.
const json* LastModelStage(const json& results) {
  const json* last = nullptr;
  for (const json& stage : results.at("stages")) {
    if (stage.contains("estimates") && stage.contains("model")) last = &stage;
  }
  return last;
}

// The last model stage's integration, interpolation, fit and estimated starts.
void ReadModelStage(const json& stage, RunDocument* d) {
  d->has_model_stage = true;
  d->integration_step = NumberOr(stage.value("integration_step", json()), RunDocument::kNaN);
  d->max_step = NumberOr(stage.value("max_step", json()), RunDocument::kNaN);
  const json interpolation = stage.value("interpolation", json::object());  // held: items() refers to it
  for (const auto& [input, method] : interpolation.items()) {
    if (method.is_string()) d->interpolation[input] = method.get<std::string>();
  }
  if (stage.contains("fit")) {
    const json metrics = stage.at("fit").value("metrics", json::array());
    for (const json& m : metrics) {
      d->fit_metrics.push_back({Text(m, "output"), Text(m, "unit"),
                                NumberOr(m.value("rmse", json()), RunDocument::kNaN),
                                NumberOr(m.value("samples", json()), RunDocument::kNaN)});
    }
  }
  for (const json& e : stage.at("estimates")) {
    ProcessNoise noise;
    if (Text(e, "kind") == "noise" &&
        ProcessNoiseNamed(Text(e, "name"), NumberOr(e.value("value", json()), RunDocument::kNaN),
                          NumberOr(e.value("std_error", json()), RunDocument::kNaN), &noise)) {
      d->process_noise.push_back(noise);
    }
    if (Text(e, "kind") != "initial_state" || Text(e, "role") != "free") continue;
    AddFreeState(Text(e, "name"), d);
  }
}

// The correlation of the last stage that has one, and its replicates; false with a message
// when it is no correlation matrix of its names.
bool ReadCorrelation(const json& results, RunDocument* d, std::string* error) {
  const json* correlated = nullptr;
  for (const json& s : results.at("stages")) {
    if (s.contains("correlation")) correlated = &s;
  }
  if (correlated == nullptr) return true;
  d->correlation_names = correlated->at("correlation").at("names").get<std::vector<std::string>>();
  const json& matrix = correlated->at("correlation").at("matrix");
  const size_t n = d->correlation_names.size();
  // A square matrix, a row and a column per name, ones on its diagonal.
  bool square = matrix.is_array() && matrix.size() == n;
  for (size_t r = 0; square && r < n; ++r) {
    square = matrix[r].is_array() && matrix[r].size() == n &&
             (matrix[r][r].is_null() ||  // undetermined
              (matrix[r][r].is_number() && std::abs(matrix[r][r].get<double>() - 1.0) < 1e-9));
  }
  if (!square) {
    *error = d->path + ": stages' correlation: not a correlation matrix of its " +
             std::to_string(n) + " names (as many rows and columns as names, 1 on the diagonal)";
    return false;
  }
  d->correlation.resize(static_cast<int>(n), static_cast<int>(n));
  for (size_t r = 0; r < n; ++r) {
    for (size_t c = 0; c < n; ++c) d->correlation(r, c) = NumberOr(matrix[r][c], RunDocument::kNaN);
  }
  const json replicates =
      correlated->value("uncertainty", json::object()).value("replicates", json::object());
  if (replicates.contains("values") && !replicates.at("values").empty()) {
    d->replicate_names = replicates.at("names").get<std::vector<std::string>>();
    for (const json& values : replicates.at("values")) {
      std::vector<double> row;
      for (const json& v : values) row.push_back(NumberOr(v, RunDocument::kNaN));
      d->replicate_values.push_back(std::move(row));
    }
  }
  return true;
}

// A number as results.json keeps it: not finite is unknown (null, read as NaN).
double Kept(double value) { return std::isfinite(value) ? value : RunDocument::kNaN; }

// The last stage's integration, interpolation, fit and estimated starts, as ReadModelStage
// reads them back.
void DescribeModelStage(const RunConfig& config, const StageResult& stage, RunDocument* d) {
  d->has_model_stage = true;
  d->integration_step = stage.integration_step > 0.0 ? stage.integration_step : RunDocument::kNaN;
  for (const StageConfig& configured : config.stages) {
    if (configured.options.name != stage.name) continue;
    if (configured.model) d->options = configured.model_options;
    d->max_step = configured.experiment.max_step;
    d->interpolation = StageInterpolation(config, configured);
  }
  for (const ExperimentFit& fit : stage.summary.fits) {
    for (const ChannelMetrics& m : fit.channels) {
      const DisplayUnit unit = OutputDisplayUnit(config, m.experiment, m.output);
      d->fit_metrics.push_back({m.output, unit.unit, Kept(unit.scale * m.rmse),
                                static_cast<double>(m.samples)});
    }
  }
  for (const Estimate& e : stage.estimates) {
    if (e.kind == EstimateKind::kInitialState && e.role == ParameterRole::kFree) {
      AddFreeState(e.name, d);
    }
  }
  d->process_noise = ProcessNoiseOf(stage.estimates);
  for (ProcessNoise& noise : d->process_noise) {
    noise.spectral_density = Kept(noise.spectral_density);
    noise.std_error = Kept(noise.std_error);
  }
}

}  // namespace

RunDocument RunDocumentOf(const RunConfig& config, const RunResult& result) {
  RunDocument d;
  d.path = config.path;
  d.family = config.family;
  d.options = config.model_options;
  if (!result.stages.empty()) DescribeModelStage(config, result.stages.back(), &d);
  for (const FinalParameter& f : result.parameters) {
    d.parameters.push_back({f.name, ParameterRoleToString(f.role), Kept(f.value), Kept(f.std_error)});
  }
  for (const StageResult& stage : result.stages) {
    const Uncertainty& u = stage.summary.uncertainty;
    if (!u.available) continue;
    d.correlation_names = stage.correlation_names;
    d.correlation = stage.correlation.unaryExpr(&Kept);
    d.replicate_names.clear();
    d.replicate_values.clear();
    if (u.bootstrap_runs > 0 && !u.replicates.empty()) {
      d.replicate_names = u.replicate_names;
      for (const std::vector<double>& values : u.replicates) {
        std::vector<double> row;
        for (double v : values) row.push_back(Kept(v));
        d.replicate_values.push_back(std::move(row));
      }
    }
  }
  d.zigzags = ZigzagEntries(result.zigzags);
  return d;
}

bool ReadRunDocument(const std::string& out_folder, RunDocument* document, std::string* error) {
  const std::string path = (fs::path(out_folder) / "results.json").string();
  std::error_code ec;
  // A run killed while publishing its results: finished first, under the folder's lock, as
  // the next command writing into it would (output_staging.h).
  if (PublicationUnfinished(out_folder) && OutputFolder::Open(out_folder, error) == nullptr) {
    *error = out_folder + ": the run's interrupted publication cannot be finished: " + *error;
    return false;
  }
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    // A FIFO or device would block or never end.
    *error = path + ": not a regular file (the results.json of a finished `vesselid run`)";
    return false;
  }
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (!ec && bytes > kMaxResultsBytes) {
    *error = path + ": " + FormatBytes(static_cast<double>(bytes)) + ", more than the " +
             FormatBytes(static_cast<double>(kMaxResultsBytes)) +
             " a run's results.json can be (its traces are CSV files beside it)";
    return false;
  }
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open (the folder of a finished `vesselid run`?)";
    return false;
  }
  try {
    const json results = json::parse(in);
    RunDocument d;
    d.path = path;
    const json& run_model = results.at("model");
    d.family = run_model.at("family");
    if (!run_model.contains("options")) {
      *error = path + ": model.options: missing (results of a vesselid older than `export`; "
                      "run the config again)";
      return false;
    }
    d.options = run_model.at("options").get<ModelOptions>();
    if (const json* stage = LastModelStage(results)) {
      if (stage->contains("model_options")) d.options = stage->at("model_options").get<ModelOptions>();
      ReadModelStage(*stage, &d);
    }
    for (const json& p : results.at("parameters")) {
      RunDocument::Parameter parameter;
      parameter.name = p.at("name").get<std::string>();
      parameter.role = p.at("role").get<std::string>();
      parameter.value = p.at("value").is_null() ? RunDocument::kNaN : p.at("value").get<double>();
      // A free parameter's standard error is part of the results, even when null.
      parameter.std_error = NumberOr(parameter.role == "free" ? p.at("std_error")
                                                              : p.value("std_error", json()),
                                     RunDocument::kNaN);
      d.parameters.push_back(std::move(parameter));
    }
    if (!ReadCorrelation(results, &d, error)) return false;
    const json zigzags = results.value("zigzags", json::array());
    for (const json& z : zigzags) {
      ZigzagEntry e;
      e.stage = Text(z, "stage");
      e.experiment = Text(z, "experiment");
      e.held_out = z.value("held_out", false);
      e.rudder_deg = NumberOr(z.value("rudder_deg", json()), RunDocument::kNaN);
      e.heading_deg = NumberOr(z.value("heading_deg", json()), RunDocument::kNaN);
      const json measured = z.value("measured", json::object());
      const json simulated = z.value("simulated", json::object());
      e.measured_first = NumberOr(measured.value("first_overshoot_deg", json()), RunDocument::kNaN);
      e.measured_second = NumberOr(measured.value("second_overshoot_deg", json()), RunDocument::kNaN);
      e.simulated_first = NumberOr(simulated.value("first_overshoot_deg", json()), RunDocument::kNaN);
      e.simulated_second =
          NumberOr(simulated.value("second_overshoot_deg", json()), RunDocument::kNaN);
      d.zigzags.push_back(std::move(e));
    }
    *document = std::move(d);
    return true;
  } catch (const json::exception& e) {
    // nlohmann's text without its "[json.exception.type_error.302] " tag.
    std::string what = e.what();
    const size_t tag = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && tag != std::string::npos) what.erase(0, tag + 2);
    *error = path + ": not the results.json of a finished `vesselid run` (" + what + ")";
    return false;
  }
}

}  // namespace vesselid
