#include "engine/output/results_writer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/base/json_number.h"
#include "engine/output/report_html.h"
#include "engine/output/step_regression_writer.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;


json MetricsToJson(const std::vector<ExperimentFit>& fits) {
  json metrics = json::array();
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) {
      metrics.push_back({{"experiment", m.experiment},
                         {"output", m.output},
                         {"samples", m.samples},
                         {"rmse", JsonNumber(m.rmse)},
                         {"mae", JsonNumber(m.mae)},
                         {"r2", JsonNumber(m.r2)},
                         {"fit_percent", JsonNumber(m.fit_percent)}});
    }
  }
  return metrics;
}

// Seed 002's per-test cost sqrt(mean e^2), by experiment.
json RmsCostToJson(const std::vector<ExperimentFit>& fits) {
  json rms = json::object();
  for (const ExperimentFit& fit : fits) rms[fit.experiment] = fit.rms_cost;
  return rms;
}

json FitsToJson(const std::vector<ExperimentFit>& fits) {
  return {{"metrics", MetricsToJson(fits)}, {"rms_cost", RmsCostToJson(fits)}};
}

json VelocityToJson(const std::vector<ChannelMetrics>& metrics);

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

json StageToJson(const StageResult& stage) {
  const StageSummary& s = stage.summary;
  json j;
  j["name"] = stage.name;
  j["model"] = stage.model;
  j["time_seconds"] = s.time_seconds;
  if (s.global.run) {
    j["global_start"] = {{"variables", s.global.variables},
                         {"evaluations", s.global.evaluations},
                         {"diverged_evaluations", s.global.failed_evaluations},
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
  j["iterations"] = s.local().iterations;
  j["notes"] = s.notes;
  json estimates = json::array();
  for (const Estimate& e : stage.estimates) {
    json item = {{"name", e.name},
                 {"kind", e.kind},
                 {"role", e.role},
                 {"value", e.value},
                 {"start", e.start},
                 {"std_error", JsonNumber(e.std_error)},
                 {"lower", JsonNumber(e.lower)},
                 {"upper", JsonNumber(e.upper)},
                 {"undetermined", e.undetermined}};
    if (!e.experiment.empty()) item["experiment"] = e.experiment;
    estimates.push_back(item);
  }
  j["estimates"] = estimates;
  const Uncertainty& u = s.uncertainty;
  j["uncertainty"] = {{"available", u.available},
                      {"message", u.message},
                      {"residual_variance", u.residual_variance},
                      {"undetermined", u.undetermined}};
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
  j["fit"] = FitsToJson(s.fits);
  j["admissibility"] = stage.admissibility;
  if (!stage.validation.empty()) j["validation"] = FitsToJson(stage.validation);
  if (!stage.velocity_validation.empty()) {
    j["velocity_validation"] = VelocityToJson(stage.velocity_validation);
  }
  if (stage.step_regression) j["step_regression"] = StepRegressionToJson(*stage.step_regression);
  return j;
}

std::string TraceFileName(const std::string& prefix, const std::string& experiment) {
  std::string name = prefix + "." + experiment + ".csv";
  for (char& c : name) {
    if (c == '/' || c == ' ') c = '_';
  }
  return name;
}

std::string MetricsRow(const ChannelMetrics& m, double rms_cost) {
  char line[256];
  std::snprintf(line, sizeof(line), "  %-20s %-8s %8d %12.4e %12.4e %10.6f %8.3f %10.4e\n",
                m.experiment.c_str(), m.output.c_str(), m.samples, m.rmse, m.mae, m.r2,
                m.fit_percent, rms_cost);
  return line;
}

// Per experiment and channel; beyond kMaxRows experiments (a campaign of segments) pooled
// per channel: RMSE and MAE over all samples, R2 and fit % as the median over experiments.
std::string MetricsTable(const std::vector<ExperimentFit>& fits) {
  constexpr size_t kMaxRows = 12;
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "  %-20s %-8s %8s %12s %12s %10s %8s %10s\n", "experiment",
                "output", "samples", "RMSE", "MAE", fits.size() > kMaxRows ? "median R2" : "R2",
                "fit %", "rms cost");
  out += line;
  if (fits.size() <= kMaxRows) {
    for (const ExperimentFit& fit : fits) {
      for (const ChannelMetrics& m : fit.channels) out += MetricsRow(m, fit.rms_cost);
    }
    return out;
  }
  std::map<std::string, std::vector<const ChannelMetrics*>> by_output;
  std::vector<std::string> order;
  double cost2 = 0.0;
  for (const ExperimentFit& fit : fits) {
    cost2 += fit.rms_cost * fit.rms_cost;
    for (const ChannelMetrics& m : fit.channels) {
      if (by_output[m.output].empty()) order.push_back(m.output);
      by_output[m.output].push_back(&m);
    }
  }
  for (const std::string& output : order) {
    const std::vector<const ChannelMetrics*>& list = by_output[output];
    ChannelMetrics pooled;
    pooled.experiment = "all " + std::to_string(fits.size());
    pooled.output = output;
    double sse = 0.0, sae = 0.0;
    std::vector<double> r2, fit;
    for (const ChannelMetrics* m : list) {
      pooled.samples += m->samples;
      sse += m->rmse * m->rmse * m->samples;
      sae += m->mae * m->samples;
      r2.push_back(m->r2);
      fit.push_back(m->fit_percent);
    }
    pooled.rmse = std::sqrt(sse / std::max(1, pooled.samples));
    pooled.mae = sae / std::max(1, pooled.samples);
    std::sort(r2.begin(), r2.end());
    std::sort(fit.begin(), fit.end());
    pooled.r2 = r2[r2.size() / 2];
    pooled.fit_percent = fit[fit.size() / 2];
    out += MetricsRow(pooled, std::sqrt(cost2 / fits.size()));
  }
  return out;
}

// One-step and free-run metrics of the regressed states.
std::string VelocityTable(const std::vector<ChannelMetrics>& metrics) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "  %-30s %-6s %8s %12s %12s %10s\n", "prediction", "state",
                "samples", "MAE", "RMSE", "R2");
  out += line;
  for (const ChannelMetrics& m : metrics) {
    std::snprintf(line, sizeof(line), "  %-30s %-6s %8d %12.4e %12.4e %10.6f\n",
                  m.experiment.c_str(), m.output.c_str(), m.samples, m.mae, m.rmse, m.r2);
    out += line;
  }
  return out;
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

std::string EstimateLine(const std::string& name, const std::string& role, double value,
                         double std_error, bool undetermined, const std::string& tail) {
  char line[512];
  if (undetermined) {
    std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %10s  %s\n", name.c_str(),
                  role.c_str(), "undetermined", "-", "-", tail.c_str());
  } else if (std::isnan(std_error)) {
    std::snprintf(line, sizeof(line), "  %-24s %-15s %16.8g %12s %10s  %s\n", name.c_str(),
                  role.c_str(), value, "-", "-", tail.c_str());
  } else {
    std::snprintf(line, sizeof(line), "  %-24s %-15s %16.8g %12.4g %10.4g  %s\n", name.c_str(),
                  role.c_str(), value, std_error, 100.0 * std_error / std::abs(value),
                  tail.c_str());
  }
  return line;
}

// Condition number, weak directions and the sensitivity table of a stage.
std::string LocalAnalysisText(const LocalAnalysis& a) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof(line),
                "  local analysis (%zu shared parameters, %d per-experiment unknowns profiled "
                "out, %.3f s): condition number %.4g\n",
                a.names.size(), a.profiled, a.time_seconds, a.condition_number);
  out << line;
  for (const WeakDirection& d : a.directions) {
    std::snprintf(line, sizeof(line), "    %s: %s (lambda/lambda_max %.3g, std %.4g along it)\n",
                  DirectionStatusToString(d.status), d.combination.c_str(), d.eigenvalue_ratio,
                  d.std_dev);
    out << line;
  }
  out << "  sensitivity: % change of the channel per % change of the parameter (S) and noise "
         "SDs per 100 % (Z)\n";
  std::snprintf(line, sizeof(line), "    %-22s", "parameter");
  out << line;
  for (const std::string& c : a.channels) {
    std::snprintf(line, sizeof(line), " %10s %10s", (c + " S").c_str(), (c + " Z").c_str());
    out << line;
  }
  out << "\n";
  for (size_t i = 0; i < a.names.size(); ++i) {
    std::snprintf(line, sizeof(line), "    %-22s", a.names[i].c_str());
    out << line;
    for (size_t c = 0; c < a.channels.size(); ++c) {
      std::snprintf(line, sizeof(line), " %10.4g %10.4g", a.sensitivity(c, i),
                    a.noise_sensitivity(c, i));
      out << line;
    }
    out << "\n";
  }
  return out.str();
}

std::string StageText(const StageResult& stage) {
  const StageSummary& s = stage.summary;
  std::ostringstream out;
  char line[512];
  out << "\n" << s.BriefReport() << " [" << stage.model << "]\n";
  if (s.global.run) out << "  " << s.global.BriefReport() << "\n";
  std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %10s\n", "name", "role", "value",
                "std error", "rel. %");
  out << line;
  for (const Estimate& e : stage.estimates) {
    if (e.role == "fixed") continue;
    out << EstimateLine(e.name, e.role, e.value, e.std_error, e.undetermined, "");
  }
  for (const std::string& note : s.notes) out << "  note: " << note << "\n";
  for (const std::string& d : s.uncertainty.undetermined) out << "  undetermined: " << d << "\n";
  for (const std::string& a : stage.admissibility) out << "  not admissible: " << a << "\n";
  if (stage.correlation.rows() > 1) {
    out << "  strongest correlations:";
    int shown = 0;
    for (int r = 0; r < stage.correlation.rows() && shown < 6; ++r) {
      for (int c = r + 1; c < stage.correlation.cols() && shown < 6; ++c) {
        if (std::abs(stage.correlation(r, c)) < 0.9) continue;
        std::snprintf(line, sizeof(line), " %s/%s %.4f;", stage.correlation_names[r].c_str(),
                      stage.correlation_names[c].c_str(), stage.correlation(r, c));
        out << line;
        ++shown;
      }
    }
    out << (shown == 0 ? " none above 0.9\n" : "\n");
  }
  if (s.analysis.available) out << LocalAnalysisText(s.analysis);
  out << MetricsTable(s.fits);
  if (!stage.validation.empty()) out << "  local validation:\n" << MetricsTable(stage.validation);
  if (!stage.velocity_validation.empty()) {
    out << "  local validation of the velocities (data: Savitzky-Golay reconstruction):\n"
        << VelocityTable(stage.velocity_validation);
  }
  return out.str();
}

bool WriteTraces(const std::string& folder, const std::string& prefix,
                 const std::vector<ExperimentFit>& fits, std::string* error) {
  for (const ExperimentFit& fit : fits) {
    const std::string path = (fs::path(folder) / TraceFileName(prefix, fit.experiment)).string();
    if (!WriteTrajectoryCsv(path, fit.trace, error)) return false;
  }
  return true;
}

}  // namespace

json RunResultToJson(const RunConfig& config, const RunResult& result) {
  json j;
  j["vesselid_version"] = "0.1.0";
  j["config"] = config.path;
  j["model"] = {{"family", config.family}, {"name", config.model->info().name}};
  j["time_seconds"] = result.time_seconds;
  json stages = json::array();
  for (const StageResult& stage : result.stages) stages.push_back(StageToJson(stage));
  j["stages"] = stages;
  j["fusion"] = FusionRuleToString(config.fusion);
  json parameters = json::array();
  for (const FinalParameter& f : result.parameters) {
    parameters.push_back({{"name", f.name},
                          {"value", f.value},
                          {"std_error", JsonNumber(f.std_error)},
                          {"role", f.role},
                          {"stages", f.stages},
                          {"rule", f.rule},
                          {"undetermined", f.undetermined}});
  }
  j["parameters"] = parameters;
  j["admissibility"] = result.admissibility;
  if (config.has_final_validation) j["final_validation"] = FitsToJson(result.final_validation);
  if (!result.final_velocity_validation.empty()) {
    j["final_velocity_validation"] = VelocityToJson(result.final_velocity_validation);
  }
  return j;
}

std::string RunResultToText(const RunConfig& config, const RunResult& result) {
  std::ostringstream out;
  out << "vesselid run of " << config.path << " (model " << config.model->info().name << ")\n";
  for (const StageResult& stage : result.stages) out << StageText(stage);
  out << "\nfinal parameters (shared: " << FusionRuleToString(config.fusion) << " fusion)\n";
  char line[256];
  std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %10s  %s\n", "name", "role", "value",
                "std error", "rel. %", "from");
  out << line;
  for (const FinalParameter& f : result.parameters) {
    std::string from;
    for (const std::string& stage : f.stages) from += (from.empty() ? "" : ", ") + stage;
    if (f.rule != "stage" && f.rule != "fixed") from += " (" + f.rule + ")";
    out << EstimateLine(f.name, f.role, f.value, f.std_error, f.undetermined && f.role != "fixed",
                        from);
  }
  for (const std::string& a : result.admissibility) out << "  not admissible: " << a << "\n";
  if (config.has_final_validation) {
    out << "\nfinal validation\n" << MetricsTable(result.final_validation);
  }
  if (!result.final_velocity_validation.empty()) {
    out << "final validation of the velocities\n"
        << VelocityTable(result.final_velocity_validation);
  }
  return out.str();
}

bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << content;
    out.flush();
    if (!out) {
      *error = temporary + ": write failed";
      return false;
    }
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    *error = path + ": " + ec.message();
    return false;
  }
  return true;
}

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error) {
  std::error_code ec;
  const std::string traces = (fs::path(out_dir) / "traces").string();
  fs::create_directories(traces, ec);
  if (ec) {
    *error = out_dir + ": cannot create folder: " + ec.message();
    return false;
  }
  for (const StageResult& stage : result.stages) {
    if (!WriteTraces(traces, stage.name, stage.summary.fits, error) ||
        !WriteTraces(traces, stage.name + ".validation", stage.validation, error)) {
      return false;
    }
  }
  if (!WriteTraces(traces, "final_validation", result.final_validation, error) ||
      !WriteStepRegressionFiles(config, result, out_dir, error) ||
      !WriteFileAtomically((fs::path(out_dir) / "report.txt").string(),
                           RunResultToText(config, result), error) ||
      !WriteRunReport(config, result, out_dir, error)) {
    return false;
  }
  return WriteFileAtomically((fs::path(out_dir) / "results.json").string(),
                             RunResultToJson(config, result).dump(2) + "\n", error);
}

}  // namespace vesselid
