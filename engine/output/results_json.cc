#include "engine/output/results_json.h"
#include "engine/run/held_out.h"

#include <map>
#include <sstream>

#include "engine/base/json_number.h"
#include "engine/base/version.h"
#include "engine/data/time_base.h"
#include "engine/output/bootstrap_report.h"
#include "engine/output/finding_report.h"
#include "engine/output/held_out_parameters_report.h"
#include "engine/output/json_splices.h"
#include "engine/output/noise_model_report.h"
#include "engine/output/parameter_summary.h"
#include "engine/output/residual_report.h"
#include "engine/output/results_json_text.h"
#include "engine/output/run_fit_table.h"
#include "engine/output/selection_report.h"
#include "engine/output/stage_interpolation.h"
#include "engine/output/step_regression_writer.h"
#include "engine/output/turning_report.h"
#include "engine/output/zigzag_report.h"
#include "engine/run/display_units.h"

namespace vesselid {
namespace {

using nlohmann::json;

// A parameter's "unit": the model's, in which results.json gives every value; where report.txt
// and report.html show it in another (a rudder bias in degrees where the rudder column was),
// that one as "shown_unit" with "shown_scale" (shown = scale x value; display_units.h).
void AddParameterUnit(const RunConfig& config, const std::string& name, json* item) {
  const std::string unit = ParameterModelUnit(config.model->info(), name);
  if (unit.empty()) return;
  (*item)["unit"] = unit;
  const DisplayUnit shown = ParameterDisplayUnit(config, name);
  if (shown.unit == unit) return;
  (*item)["shown_unit"] = shown.unit;
  (*item)["shown_scale"] = shown.scale;
}

json VelocityToJson(const std::vector<ChannelMetrics>& metrics) {
  json j = json::array();
  for (const ChannelMetrics& m : metrics) {
    j.push_back({{"prediction", m.experiment},
                 {"state", m.output},
                 {"samples", m.samples},
                 {"mae", JsonNumber(m.mae)},
                 {"rmse", JsonNumber(m.rmse)},
                 {"r2", JsonNumber(m.r2)}});
  }
  return j;
}

// RMSE, MAE, hold MAE and noise in `unit` (display_units.h: degrees where the data were).
json MetricsToJson(const RunConfig& config, const std::vector<ExperimentFit>& fits,
                   JsonSplices* splices) {
  std::vector<const ChannelMetrics*> channels;
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) channels.push_back(&m);
  }
  return JsonSplices::ArrayIn(splices, channels.size(), [&config, channels](size_t i) -> json {
    const ChannelMetrics& m = *channels[i];
    const DisplayUnit unit = OutputDisplayUnit(config, m.experiment, m.output);
    return {{"experiment", m.experiment},
            {"output", m.output},
            {"unit", unit.unit},
            {"samples", m.samples},
            {"rmse", JsonNumber(unit.scale * m.rmse)},
            {"mae", JsonNumber(unit.scale * m.mae)},
            {"r2", JsonNumber(m.r2)},
            {"fit_percent", JsonNumber(m.fit_percent)},
            {"hold_mae", JsonNumber(unit.scale * m.hold_mae)},
            {"noise", JsonNumber(unit.scale * m.noise)}};
  });
}

// One row per run with its segments folded in, and the mean / median / worst (run_fit_table.h).
json RunsToJson(const RunConfig& config, const std::vector<ExperimentFit>& fits) {
  const RunFitTable table = PerRunFits(config, fits);
  json runs = json::array();
  for (const RunFitRow& row : table.rows) {
    json outputs = json::object();
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      const ChannelMetrics& m = row.channels[o];
      if (m.samples == 0) continue;
      outputs[m.output] = {{"samples", m.samples},
                           {"rmse", JsonNumber(m.rmse)},
                           {"mae", JsonNumber(m.mae)},
                           {"r2", JsonNumber(m.r2)},
                           {"fit_percent", JsonNumber(m.fit_percent)}};
    }
    runs.push_back({{"run", row.run},
                    {"segments", row.segments},
                    {"diverged", row.diverged},
                    {"rms_cost", JsonNumber(row.rms_cost)},
                    {"outputs", outputs}});
  }
  json summary = json::object();
  for (const RunFitSummary& s : table.summary) {
    json outputs = json::object();
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      outputs[table.outputs[o]] = {{"fit_percent", JsonNumber(s.fit_percent[o])},
                                   {"rmse", JsonNumber(s.rmse[o])}};
      if (!s.run[o].empty()) outputs[table.outputs[o]]["run"] = s.run[o];
    }
    summary[s.label] = outputs;
  }
  json units = json::object();
  for (size_t o = 0; o < table.outputs.size(); ++o) units[table.outputs[o]] = table.units[o];
  return {
      {"rows", runs}, {"summary", summary}, {"units", units}, {"worst_first", table.worst_first}};
}

json DisturbanceToJson(const DisturbanceReport& d) {
  json candidates = json::array();
  for (const DisturbanceCandidateScore& c : d.candidates) {
    json row = {{"name", c.name},
                {"solved", c.solved},
                {"negative_log_likelihood", JsonNumber(c.negative_log_likelihood)},
                {"unknowns", c.unknowns},
                {"bic", JsonNumber(c.bic)},
                {"chosen", c.chosen}};
    if (!c.why.empty()) row["why"] = c.why;
    candidates.push_back(row);
  }
  json predictions = json::array();
  for (const FilterPrediction& p : d.predictions) {
    predictions.push_back({{"experiment", p.experiment},
                           {"output", p.output},
                           {"steps", p.steps},
                           {"seconds_ahead", JsonNumber(p.seconds_ahead)},
                           {"k_step_fit_percent", JsonNumber(p.k_step_fit_percent)},
                           {"one_step_fit_percent", JsonNumber(p.one_step_fit_percent)},
                           {"free_run_fit_percent", JsonNumber(p.free_run_fit_percent)}});
  }
  return {{"method", d.method},
          {"model", d.model},
          {"negative_log_likelihood", JsonNumber(d.negative_log_likelihood)},
          {"candidates", candidates},
          {"predictions", predictions}};
}

json CountsToJson(const UnknownCounts& c) {
  return {{"shared_parameters", c.shared},
          {"per_experiment_parameters", c.per_experiment},
          {"per_experiment_values", c.per_experiment_values},
          {"fixed_parameters", c.fixed},
          {"initial_states", c.initial_states}};
}

// Experiments whose simulation diverged, with the reason.
json DivergedToJson(const std::vector<ExperimentFit>& fits) {
  json diverged = json::object();
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) diverged[fit.experiment] = fit.message;
  }
  return diverged;
}

json HeldOutToJson(const HeldOutCheck& check) {
  json outputs = json::array();
  for (size_t i = 0; i < check.outputs.size(); ++i) {
    outputs.push_back({{"output", check.outputs[i]},
                       {"start_mae", JsonNumber(check.start_mae[i])},
                       {"stage_mae", JsonNumber(check.stage_mae[i])}});
  }
  return {{"outputs", outputs},
          {"start_diverged", check.start_diverged},
          {"stage_diverged", check.stage_diverged},
          {"start_far_worse", check.start_far_worse},
          {"worse", check.worse}};
}

// Seed 002's per-test cost sqrt(mean e^2), by experiment.
json RmsCostToJson(const std::vector<ExperimentFit>& fits, JsonSplices* splices) {
  std::vector<std::string> names;
  names.reserve(fits.size());
  for (const ExperimentFit& fit : fits) names.push_back(fit.experiment);
  return JsonSplices::ObjectIn(splices, std::move(names),
                               [&fits](size_t i) { return JsonNumber(fits[i].rms_cost); });
}

// How each held-out run was started and scored (HeldOutStartReport); null for training fits.
json StartsToJson(const RunConfig& config, const std::vector<ExperimentFit>& fits) {
  json starts = json::object();
  for (const ExperimentFit& fit : fits) {
    const HeldOutStartReport& s = fit.start;
    if (s.mode.empty()) continue;
    json j = {{"mode", s.mode},
              {"burn_in_s", JsonNumber(s.burn_in)},
              {"estimated", s.estimated},
              {"weighed", s.weighed}};
    if (s.requested_burn_in > 0.0) j["requested_burn_in_s"] = JsonNumber(s.requested_burn_in);
    if (s.mode == "refitted") j["refitted"] = s.refitted;
    if (!s.offsets.empty() || !s.measured_start.empty() || s.measured_start_diverged) {
      json measured = json::object();
      for (const ChannelMetrics& m : s.measured_start) {
        const DisplayUnit unit = OutputDisplayUnit(config, fit.experiment, m.output);
        measured[m.output] = {{"fit_percent", JsonNumber(m.fit_percent)},
                              {"rmse", JsonNumber(unit.scale * m.rmse)},
                              {"r2", JsonNumber(m.r2)}};
      }
      j["measured_start"] = measured;
      j["measured_start_diverged"] = s.measured_start_diverged;
      json offsets = json::array();
      for (const StartOffset& o : s.offsets) {
        const DisplayUnit unit = OutputDisplayUnit(config, fit.experiment, o.state);
        offsets.push_back({{"state", o.state},
                           {"unit", unit.unit},
                           {"measured", JsonNumber(unit.scale * o.measured)},
                           {"refitted", JsonNumber(unit.scale * o.refitted)},
                           {"noise", JsonNumber(unit.scale * o.noise)},
                           {"sds", JsonNumber(o.sds)}});
      }
      j["refitted_offsets"] = offsets;
      j["implausible_sds"] = JsonNumber(s.implausible_sds);
    }
    starts[fit.experiment] = j;
  }
  return starts;
}

// Each held-out run's prediction band (prediction_band.h), by experiment.
json BandsToJson(const std::vector<ExperimentFit>& fits) {
  json bands = json::object();
  for (const ExperimentFit& fit : fits) {
    const PredictionBand& b = fit.band;
    if (!b.done) continue;
    json outputs = json::object();
    for (size_t o = 0; o < b.outputs.size(); ++o) outputs[b.outputs[o]] = JsonNumber(b.output_ratio[o]);
    bands[fit.experiment] = {{"samples", b.samples},
                             {"ratio", JsonNumber(b.ratio)},
                             {"raw_ratio", JsonNumber(b.raw_ratio)},
                             {"output_raw_ratio", outputs}};
  }
  return bands;
}

json FitsToJson(const RunConfig& config, const std::vector<ExperimentFit>& fits,
                JsonSplices* splices) {
  json j = {{"metrics", MetricsToJson(config, fits, splices)},
            {"rms_cost", RmsCostToJson(fits, splices)},
            {"runs", RunsToJson(config, fits)}};
  const json starts = StartsToJson(config, fits);
  if (!starts.empty()) j["start"] = starts;
  const json diverged = DivergedToJson(fits);
  if (!diverged.empty()) j["diverged"] = diverged;
  const json bands = BandsToJson(fits);
  if (!bands.empty()) j["prediction_band"] = bands;
  return j;
}

// Conditioning and sensitivities at the optimum (local_analysis.h); null numbers are
// infinite or unknown (an infinite condition number: the information matrix is singular).
json LocalAnalysisToJson(const LocalAnalysis& a) {
  json j = {{"available", a.available}};
  if (!a.available) {
    j["message"] = a.message;
    return j;
  }
  j["parameters"] = a.names;
  j["profiled"] = a.profiled;
  j["residual_variance"] = a.residual_variance;
  j["condition_number"] = JsonNumber(a.condition_number);
  json ratios = json::array();
  const double lambda_max = std::max(a.eigenvalues.maxCoeff(), 0.0);
  for (int k = 0; k < a.eigenvalues.size(); ++k) {
    ratios.push_back(JsonNumber(lambda_max > 0 ? a.eigenvalues[k] / lambda_max : 0.0));
  }
  j["eigenvalue_ratios"] = ratios;
  json directions = json::array();
  for (const WeakDirection& d : a.directions) {
    json coefficients = json::object();
    for (size_t i = 0; i < a.names.size(); ++i) {
      if (d.coefficients[i] != 0.0) coefficients[a.names[i]] = d.coefficients[i];
    }
    directions.push_back({{"combination", d.combination},
                          {"coefficients", coefficients},
                          {"eigenvalue_ratio", d.eigenvalue_ratio},
                          {"std_dev", JsonNumber(d.std_dev)},
                          {"std_dev_normalised", JsonNumber(d.std_dev_normalised)},
                          {"status", DirectionStatusToString(d.status)}});
  }
  j["directions"] = directions;
  json std_errors = json::object();
  for (size_t i = 0; i < a.names.size(); ++i) std_errors[a.names[i]] = JsonNumber(a.std_errors[i]);
  j["std_errors"] = std_errors;
  auto table = [&](const Eigen::MatrixXd& values) {
    json t = json::object();
    for (size_t c = 0; c < a.channels.size(); ++c) {
      json row = json::object();
      for (size_t i = 0; i < a.names.size(); ++i) row[a.names[i]] = JsonNumber(values(c, i));
      t[a.channels[c]] = row;
    }
    return t;
  };
  j["sensitivity"] = table(a.sensitivity);
  j["noise_sensitivity"] = table(a.noise_sensitivity);
  j["time_seconds"] = a.time_seconds;
  return j;
}

json StageToJson(const RunConfig& config, const StageResult& stage, JsonSplices* splices) {
  const StageSummary& s = stage.summary;
  json j;
  j["name"] = stage.name;
  j["verdict"] = VerdictToString(stage.verdict);
  j["findings"] = FindingsToJson(stage.findings);
  j["model"] = stage.model;
  for (const StageConfig& configured : config.stages) {
    if (configured.options.name != stage.name) continue;
    if (configured.model) j["model_options"] = configured.model_options;  // its restriction
    // The configured bound on the RK4 step (0: the median sample interval);
    // integration_step below when the stage had to shorten it.
    j["max_step"] = configured.experiment.max_step;
    j["interpolation"] = StageInterpolation(config, configured);
  }
  j["time_seconds"] = s.time_seconds;
  if (s.global.run) {
    j["global_start"] = {{"algorithm", s.global.algorithm},
                         {"variables", s.global.variables},
                         {"horizon_seconds", s.global.horizon_seconds},
                         {"evaluations", s.global.evaluations},
                         {"diverged_evaluations", s.global.failed_evaluations},
                         {"abandoned", s.global.abandoned},
                         {"distinct_end_points", s.global.clusters},
                         {"best_cost", s.global.best_cost},
                         {"candidate_costs", s.global.candidate_costs},
                         {"time_seconds", s.global.time_seconds},
                         {"result", s.global.result}};
  }
  json refinements = json::array();
  for (const LocalSolveSummary& l : s.refinements) {
    refinements.push_back({{"initial_cost", JsonNumber(l.initial_cost)},
                           {"final_cost", JsonNumber(l.final_cost)},
                           {"iterations", l.iterations},
                           {"time_seconds", l.time_seconds},
                           {"termination", l.termination},
                           {"usable", l.usable}});
  }
  j["refinements"] = refinements;
  j["chosen_refinement"] = s.chosen;
  j["cost"] = s.local().final_cost;
  // The cost at the estimate with the configured weights: comparable across end points,
  // starts, runs and tools whatever the noise model did (StageResult::comparable_cost).
  j["comparable_cost"] = JsonNumber(stage.comparable_cost);
  j["comparable_cost_weights"] = "configured";
  j["iterations"] = s.local().iterations;
  j["notes"] = s.notes;
  j["counts"] = CountsToJson(CountUnknowns(stage.estimates));
  // Another method than the Hessian reported: the Hessian's standard error beside it.
  std::map<std::string, double> hessian;
  const std::vector<double>& hessian_std_errors = s.uncertainty.hessian_std_errors;
  for (size_t i = 0; i < hessian_std_errors.size() && i < stage.correlation_names.size(); ++i) {
    hessian[stage.correlation_names[i]] = hessian_std_errors[i];
  }
  auto estimate = [&config, &stage, hessian = std::move(hessian)](size_t i) {
    const Estimate& e = stage.estimates[i];
    json item = {{"name", e.name},
                 {"kind", EstimateKindToString(e.kind)},
                 {"role", ParameterRoleToString(e.role)},
                 {"value", e.value},
                 {"start", JsonNumber(e.start)},
                 {"std_error", JsonNumber(e.std_error)},
                 {"lower", JsonNumber(e.lower)},
                 {"upper", JsonNumber(e.upper)},
                 {"undetermined", e.undetermined}};
    if (!e.experiment.empty()) item["experiment"] = e.experiment;
    AddParameterUnit(config, e.name, &item);
    const auto found = hessian.find(e.name);
    if (found != hessian.end()) item["std_error_hessian"] = JsonNumber(found->second);
    return item;
  };
  j["estimates"] = JsonSplices::ArrayIn(splices, stage.estimates.size(), estimate);
  const Uncertainty& u = s.uncertainty;
  j["uncertainty"] = {{"available", u.available},
                      {"message", u.message},
                      {"residual_variance", u.residual_variance},
                      {"undetermined", u.undetermined},
                      {"method", u.method},
                      {"method_reason", u.method_reason}};
  if (u.method == "sandwich_hac") j["uncertainty"]["bandwidth"] = u.hac_bandwidth;
  if (u.bootstrap_runs > 0) {
    j["uncertainty"]["runs"] = u.bootstrap_runs;
    j["uncertainty"]["failed"] = u.bootstrap_failed;
    if (u.method == "block_bootstrap") j["uncertainty"]["block_length"] = u.block_length;
    // The replicates' estimates: `vesselid export` takes its ensemble from them.
    j["uncertainty"]["replicates"] = {{"names", u.replicate_names}, {"values", u.replicates}};
  }
  if (u.input_noise_runs > 0) {
    // The input noise's part of each standard error, by name (the matrix's variables are the
    // reported ones unless latent-input corrections are among them).
    json parts = json::object();
    if (u.input_noise_std_errors.size() == stage.correlation_names.size()) {
      for (size_t i = 0; i < u.input_noise_std_errors.size(); ++i) {
        parts[stage.correlation_names[i]] = JsonNumber(u.input_noise_std_errors[i]);
      }
    }
    j["uncertainty"]["input_noise"] = {{"runs", u.input_noise_runs},
                                       {"failed", u.input_noise_failed},
                                       {"inputs", u.input_noise_inputs},
                                       {"std_errors", parts},
                                       {"residual_share", u.input_noise_share}};
  }
  if (u.available) {
    json matrix = json::array();
    for (int r = 0; r < stage.correlation.rows(); ++r) {
      json row = json::array();
      for (int c = 0; c < stage.correlation.cols(); ++c) {
        row.push_back(JsonNumber(stage.correlation(r, c)));
      }
      matrix.push_back(row);
    }
    j["correlation"] = {{"names", stage.correlation_names}, {"matrix", matrix}};
  }
  if (s.analysis.available || !s.analysis.message.empty()) {
    j["local_analysis"] = LocalAnalysisToJson(s.analysis);
  }
  j["fit"] = FitsToJson(config, s.fits, splices);
  j["admissibility"] = stage.admissibility;
  if (!stage.validation.empty()) j["validation"] = FitsToJson(config, stage.validation, splices);
  if (!stage.validation_residuals.empty()) {
    j["validation"]["residual_analysis"] =
        ResidualAnalysesToJson(stage.validation_residuals, splices);
  }
  if (stage.held_out.done) j["held_out_check"] = HeldOutToJson(stage.held_out);
  if (stage.held_out_parameters.active()) {
    j["held_out_parameters"] = HeldOutParametersToJson(stage.held_out_parameters, stage.validation);
  }
  if (!stage.rejected.empty()) j["rejected"] = stage.rejected;
  if (stage.integration_step > 0.0) j["integration_step"] = stage.integration_step;
  if (stage.noise_model.active()) j["noise_model"] = NoiseModelToJson(config, stage);
  if (stage.disturbance.active()) j["disturbance"] = DisturbanceToJson(stage.disturbance);
  if (!stage.velocity_validation.empty()) {
    j["velocity_validation"] = VelocityToJson(stage.velocity_validation);
  }
  if (stage.step_regression) j["step_regression"] = StepRegressionToJson(*stage.step_regression);
  if (!stage.residuals.empty()) {
    j["residual_analysis"] = ResidualAnalysesToJson(stage.residuals, splices);
  }
  if (stage.bootstrap.done() || !stage.bootstrap.message.empty()) {
    j["bootstrap"] = BootstrapToJson(stage.bootstrap);
  }
  return j;
}

// The document, its per-experiment arrays in `splices` when given (RunResultToJson,
// WriteRunResultJson).
json RunResultDocument(const RunConfig& config, const RunResult& result, JsonSplices* splices) {
  json j;
  j["vesselid_version"] = kVersion;
  // The verdict first: a reader (or a script) sees it before anything else.
  j["config"] = config.path;
  // Enough to make the model again (ModelRegistry::MakeModel): `vesselid export`.
  j["model"] = {{"family", config.family},
                {"name", config.model->info().name},
                {"options", config.model_options}};
  j["time_seconds"] = result.time_seconds;
  j["verdict"] = VerdictToString(result.verdict);
  j["findings"] = FindingsToJson(result.findings);
  // Where relative times (epoch logs) and local positions (GNSS) start, per experiment.
  for (const RecordOrigin& o : result.record_origins) {
    json& origin = j["record_origins"][o.experiment];
    if (o.epoch) {
      origin["time_origin_unix"] = FormatNanoseconds(o.time_origin_ns);  // exact decimal text
      origin["time_origin_utc"] = FormatUtc(o.time_origin_ns);
    }
    if (o.position) origin["position_origin"] = {{"lat", o.lat}, {"lon", o.lon}};
  }
  if (!result.stopped_stage.empty()) {
    j["stopped"] = {{"stage", result.stopped_stage}, {"message", result.stop_message}};
  }
  j["final"] = FinalChoiceToString(config.final_choice);
  json stages = json::array();
  for (const StageResult& stage : result.stages) {
    stages.push_back(StageToJson(config, stage, splices));
  }
  j["stages"] = stages;
  j["fusion"] = FusionRuleToString(config.fusion);
  json parameters = json::array();
  const std::vector<ParameterReport> reports = ReportParameters(result);
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    const FinalParameter& f = result.parameters[i];
    const ParameterReport& r = reports[i];
    json item = {{"name", f.name},
                 {"value", f.value},
                 {"std_error", JsonNumber(f.std_error)},
                 {"role", ParameterRoleToString(f.role)},
                 {"stages", f.stages},
                 {"rule", f.rule},
                 {"undetermined", f.undetermined},
                 {"interval", {JsonNumber(r.interval_low), JsonNumber(r.interval_high)}},
                 {"interval_clipped", r.clipped},
                 {"bounds", {JsonNumber(r.lower), JsonNumber(r.upper)}}};
    AddParameterUnit(config, f.name, &item);
    if (r.bound != 0) item["at_bound"] = r.bound < 0 ? "lower" : "upper";
    if (!r.fusion_note.empty()) item["fusion_note"] = r.fusion_note;
    if (f.runs > 0) {  // per_experiment: one value per run
      item["runs"] = {
          {"count", f.runs}, {"min", JsonNumber(f.runs_min)}, {"max", JsonNumber(f.runs_max)}};
    }
    parameters.push_back(item);
  }
  j["parameters"] = parameters;
  j["counts"] = CountsToJson(CountUnknowns(result));
  j["admissibility"] = result.admissibility;
  if (config.has_final_validation) {
    j["final_validation"] = FitsToJson(config, result.final_validation, splices);
    if (!result.final_validation_residuals.empty()) {
      j["final_validation"]["residual_analysis"] =
          ResidualAnalysesToJson(result.final_validation_residuals, splices);
    }
    if (result.reference_check.done) {
      const HeldOutCheck& check = result.reference_check;
      json outputs = json::array();
      const std::string first =
          result.final_validation.empty() ? "" : result.final_validation[0].experiment;
      for (size_t i = 0; i < check.outputs.size(); ++i) {  // in the metrics' display units
        const DisplayUnit unit = OutputDisplayUnit(config, first, check.outputs[i]);
        outputs.push_back({{"output", check.outputs[i]},
                           {"unit", unit.unit},
                           {"reference_mae", JsonNumber(unit.scale * check.start_mae[i])},
                           {"final_mae", JsonNumber(unit.scale * check.stage_mae[i])}});
      }
      j["final_validation"]["reference"] = {
          {"folder", config.final_validation.reference.folder},
          {"outputs", outputs},
          {"runs", result.final_validation.size()},
          {"reference_diverged", check.start_diverged},
          {"final_diverged", check.stage_diverged},
          {"mean_mae_ratio", JsonNumber(MeanMaeRatio(check))},
          {"worse", check.worse}};
    }
  }
  if (result.final_held_out_parameters.active()) {
    j["final_held_out_parameters"] =
        HeldOutParametersToJson(result.final_held_out_parameters, result.final_validation);
  }
  if (!result.final_velocity_validation.empty()) {
    j["final_velocity_validation"] = VelocityToJson(result.final_velocity_validation);
  }
  if (!result.zigzags.empty()) j["zigzags"] = ZigzagRunsToJson(result.zigzags);
  if (result.selection) j["selection"] = SelectionToJson(*result.selection);
  if (!result.turning_circles.empty()) {
    j["turning_circles"] = TurningRunsToJson(result.turning_circles);
  }
  return j;
}

}  // namespace

json RunResultToJson(const RunConfig& config, const RunResult& result) {
  return RunResultDocument(config, result, nullptr);
}

void WriteRunResultJson(const RunConfig& config, const RunResult& result, int indent,
                        std::ostream* out) {
  JsonSplices splices;
  const json document = RunResultDocument(config, result, &splices);
  splices.Write(document, indent, out);
}

std::string RunResultJsonText(const RunConfig& config, const RunResult& result, int indent) {
  std::ostringstream text;
  WriteRunResultJson(config, result, indent, &text);
  return text.str();
}

}  // namespace vesselid
