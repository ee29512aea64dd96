#include "engine/output/results_text.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/output/held_out_parameters_report.h"
#include "engine/output/zigzag_report.h"
#include "engine/run/held_out.h"

namespace vesselid {
namespace {

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
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) out += "  " + fit.experiment + ": " + fit.message + "\n";
  }
  if (fits.size() <= kMaxRows) {
    for (const ExperimentFit& fit : fits) {
      for (const ChannelMetrics& m : fit.channels) out += MetricsRow(m, fit.rms_cost);
    }
    return out;
  }
  std::map<std::string, std::vector<const ChannelMetrics*>> by_output;
  std::vector<std::string> order;
  double cost2 = 0.0;
  int measured = 0;
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) continue;
    ++measured;
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
    out += MetricsRow(pooled, std::sqrt(cost2 / std::max(1, measured)));
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
    if (e.role == ParameterRole::kFixed) continue;
    out << EstimateLine(e.name, ParameterRoleToString(e.role), e.value, e.std_error, e.undetermined,
                        "");
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
  out << HeldOutParametersText(stage.held_out_parameters, stage.validation, "  ");
  if (stage.held_out.done) {
    out << "  held-out check against the stage's start: " << DescribeHeldOut(stage.held_out)
        << (stage.held_out.worse ? " (worse)" : " (not worse)") << "\n";
  }
  if (!stage.rejected.empty()) out << "  set aside: " << stage.rejected << "\n";
  if (!stage.velocity_validation.empty()) {
    out << "  local validation of the velocities (data: Savitzky-Golay reconstruction):\n"
        << VelocityTable(stage.velocity_validation);
  }
  return out.str();
}

}  // namespace

std::string RunResultToText(const RunConfig& config, const RunResult& result) {
  std::ostringstream out;
  out << "vesselid run of " << config.path << " (model " << config.model->info().name << ")\n";
  if (!result.stopped_stage.empty()) {
    out << "STOPPED in stage '" << result.stopped_stage << "': " << result.stop_message << "\n";
  }
  if (!result.warnings.empty()) {
    out << "\nwarnings (" << result.warnings.size() << ")\n";
    for (const std::string& w : result.warnings) out << "  warning: " << w << "\n";
  }
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
    const bool fixed = f.role == ParameterRole::kFixed;
    if (f.runs > 0) {  // per_experiment: its values per run, not one value
      char runs[320];
      std::snprintf(runs, sizeof(runs),
                    "  %-24s %-15s %16s %12s %10s  %d runs from %.6g to %.6g (start %.6g), %s\n",
                    f.name.c_str(), ParameterRoleToString(f.role), "per run", "-", "-", f.runs,
                    f.runs_min, f.runs_max, f.value, from.c_str());
      out << runs;
      continue;
    }
    out << EstimateLine(f.name, ParameterRoleToString(f.role), f.value, f.std_error,
                        f.undetermined && !fixed, from);
  }
  for (const std::string& a : result.admissibility) out << "  not admissible: " << a << "\n";
  if (config.has_final_validation) {
    out << "\nfinal validation\n" << MetricsTable(result.final_validation)
        << HeldOutParametersText(result.final_held_out_parameters, result.final_validation, "  ");
  }
  if (!result.final_velocity_validation.empty()) {
    out << "final validation of the velocities\n"
        << VelocityTable(result.final_velocity_validation);
  }
  out << ZigzagRunsText(result.zigzags);
  return out.str();
}

}  // namespace vesselid
