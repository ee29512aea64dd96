#include "engine/output/results_text.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/output/bootstrap_report.h"
#include "engine/output/finding_report.h"
#include "engine/output/held_out_parameters_report.h"
#include "engine/output/held_out_start_text.h"
#include "engine/output/noise_model_report.h"
#include "engine/output/parameter_summary.h"
#include "engine/output/residual_report.h"
#include "engine/output/run_fit_table.h"
#include "engine/output/selection_report.h"
#include "engine/output/shown_parameters.h"
#include "engine/output/turning_report.h"
#include "engine/output/zigzag_report.h"
#include "engine/run/held_out.h"

namespace vesselid {
namespace {

// An equation-error fit: per regressed equation its samples, RMS residual and R2.
std::string RegressionTable(const std::vector<ExperimentFit>& fits) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "  %-20s %-8s %8s %12s %10s\n", "fit", "equation", "samples",
                "RMS", "R2");
  out += line;
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) {
      std::snprintf(line, sizeof(line), "  %-20s %-8s %8d %12.4e %10.6f\n", m.experiment.c_str(),
                    m.output.c_str(), m.samples, m.rmse, m.r2);
      out += line;
    }
  }
  return out;
}

// One row per run, its segments folded in, with mean / median / worst (run_fit_table.h); an
// equation-error fit as its regression table.
std::string TextMetricsTable(const RunConfig& config, const std::vector<ExperimentFit>& fits) {
  for (const ExperimentFit& fit : fits) {
    if (IsSimulationFit(fit) || fit.diverged) return RunFitTableText(PerRunFits(config, fits));
  }
  return fits.empty() ? "" : RegressionTable(fits);
}

// One-step and free-run metrics of the regressed states.
std::string TextVelocityTable(const std::vector<ChannelMetrics>& metrics) {
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

std::string StageText(const RunConfig& config, const StageResult& stage) {
  const StageSummary& s = stage.summary;
  std::ostringstream out;
  char line[512];
  out << "\n" << s.BriefReport() << " [" << stage.model << "]\n";
  out << "  " << VerdictLine(stage.verdict, stage.findings) << "\n";
  if (std::isfinite(stage.comparable_cost)) {
    std::snprintf(line, sizeof(line), "  comparable cost (configured weights): %.6e\n",
                  stage.comparable_cost);
    out << line;
  }
  out << "  " << DescribeCounts(CountUnknowns(stage.estimates)) << "\n";
  if (s.global.run) out << "  " << s.global.BriefReport() << "\n";
  std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %10s  %s\n", "name", "role",
                "value", "std error", "rel. %", "unit");
  out << line;
  for (const Estimate& estimate : stage.estimates) {
    if (estimate.role == ParameterRole::kFixed) continue;
    const DisplayUnit unit = ParameterDisplayUnit(config, estimate.name);
    const Estimate e = Shown(estimate, unit);
    out << EstimateLine(e.name, ParameterRoleToString(e.role), e.value, e.std_error, e.undetermined,
                        unit.unit);
  }
  if (s.uncertainty.available) {
    out << "  uncertainty: " << s.uncertainty.method
        << (s.uncertainty.method_reason.empty() ? "" : " (" + s.uncertainty.method_reason + ")")
        << "\n";
  }
  out << NoiseModelText(config, stage);
  out << FindingsText(stage.findings, true, "  ");
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
  out << BootstrapText(stage);
  out << TextMetricsTable(config, s.fits);
  out << ResidualAnalysesText(stage.residuals, "  ");
  if (!stage.validation.empty()) {
    out << "  local validation: " << HeldOutStartSentence(stage.validation) << "\n"
        << TextMetricsTable(config, stage.validation) << HeldOutStartTable(stage.validation, "  ")
        << ResidualAnalysesText(stage.validation_residuals, "  ");
  }
  out << HeldOutParametersText(stage.held_out_parameters, stage.validation, "  ",
                               ParameterUnits(config));
  if (stage.held_out.done) {
    out << "  held-out check against the stage's start: " << DescribeHeldOut(stage.held_out)
        << (stage.held_out.worse ? " (worse)" : " (not worse)") << "\n";
  }
  if (!stage.rejected.empty()) out << "  set aside: " << stage.rejected << "\n";
  if (!stage.velocity_validation.empty()) {
    out << "  local validation of the velocities (data: Savitzky-Golay reconstruction):\n"
        << TextVelocityTable(stage.velocity_validation);
  }
  return out.str();
}

// The final parameters with their 95 % intervals (clipped to the bounds and flagged), the
// stages behind each, the counts and the fusion notes.
std::string FinalParametersText(const RunConfig& config, const RunResult& result) {
  std::ostringstream out;
  out << "  final parameters (shared: " << FusionRuleToString(config.fusion)
      << " fusion): " << DescribeCounts(CountUnknowns(result)) << "\n";
  char line[512];
  std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %27s %-6s %s\n", "name", "role",
                "value", "std error", "95 % interval", "unit", "from");
  out << line;
  const std::vector<ParameterReport> reports = ReportParameters(result);
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    const DisplayUnit unit = ParameterDisplayUnit(config, result.parameters[i].name);
    const FinalParameter f = Shown(result.parameters[i], unit);
    const ParameterReport r = Shown(reports[i], unit);
    std::string from;
    for (const std::string& stage : f.stages) from += (from.empty() ? "" : ", ") + stage;
    if (f.rule != "stage" && f.rule != "fixed") from += " (" + f.rule + ")";
    const std::string flags = ParameterFlags(r, unit.unit);
    if (!flags.empty()) from += "  ** " + flags;
    const bool fixed = f.role == ParameterRole::kFixed;
    std::string value = "-", error = "-", interval = fixed ? "-" : "undetermined";
    char cell[96];
    std::snprintf(cell, sizeof(cell), "%.8g", f.value);
    value = cell;
    if (std::isfinite(f.std_error) && !(f.undetermined && !fixed)) {
      std::snprintf(cell, sizeof(cell), "%.4g", f.std_error);
      error = cell;
    }
    if (f.undetermined && !fixed) value = "undetermined";
    if (f.runs > 0) {  // per_experiment: its values per run, not one value
      std::snprintf(cell, sizeof(cell), "%d runs: %.6g to %.6g", f.runs, f.runs_min, f.runs_max);
      value = "per run";
      error = "-";
      interval = cell;
    } else if (std::isfinite(r.interval_low)) {
      std::snprintf(cell, sizeof(cell), "[%.6g, %.6g]", r.interval_low, r.interval_high);
      interval = cell;
    }
    std::snprintf(line, sizeof(line), "  %-24s %-15s %16s %12s %27s %-6s %s\n", f.name.c_str(),
                  ParameterRoleToString(f.role), value.c_str(), error.c_str(), interval.c_str(),
                  unit.unit.c_str(), from.c_str());
    out << line;
  }
  for (const ParameterReport& r : reports) {
    if (!r.fusion_note.empty()) out << "  note: " << r.fusion_note << "\n";
  }
  for (const std::string& a : result.admissibility) out << "  not admissible: " << a << "\n";
  return out.str();
}

}  // namespace

std::string RunResultToText(const RunConfig& config, const RunResult& result) {
  std::ostringstream out;
  const std::vector<Finding> all = AllFindings(result);
  // The verdict is the first line (run_findings.h states its rule).
  out << VerdictLine(result.verdict, all) << "\n";
  out << "vesselid run of " << config.path << " (model " << config.model->info().name << ")\n";
  if (!result.stopped_stage.empty()) {
    out << "STOPPED in stage '" << result.stopped_stage << "': " << result.stop_message << "\n";
  }
  // Summary first: what a reader needs to judge the result, then the details by stage.
  out << "\nsummary\n" << FinalParametersText(config, result);
  if (const StageResult* last = LastAcceptedStage(result)) {
    out << "\n  fit per run, stage '" << last->name << "' (identification data):\n"
        << TextMetricsTable(config, last->summary.fits);
  }
  if (config.has_final_validation && !result.final_validation.empty()) {
    out << "\n  fit per run, final values on held-out data:\n  "
        << HeldOutStartSentence(result.final_validation) << "\n"
        << TextMetricsTable(config, result.final_validation);
  }
  if (all.empty()) {
    out << "\nfindings: none\n";
  } else {
    out << "\nfindings (" << all.size() << ")\n" << FindingsText(all, true, "  ");
  }
  out << "\nstages\n";
  for (const StageResult& stage : result.stages) out << StageText(config, stage);
  if (config.has_final_validation) {
    out << "\nfinal validation\n  " << HeldOutStartSentence(result.final_validation) << "\n"
        << TextMetricsTable(config, result.final_validation)
        << HeldOutStartTable(result.final_validation, "  ")
        << ResidualAnalysesText(result.final_validation_residuals, "  ")
        << HeldOutParametersText(result.final_held_out_parameters, result.final_validation, "  ",
                                 ParameterUnits(config));
    if (result.reference_check.done) {
      out << "  against the reference model (" << config.final_validation.reference.folder
          << "): "
          << DescribeReferenceCheck(result, OutputUnits(config))
          << (result.reference_check.worse ? " (worse)" : " (not worse)") << "\n";
    }
  }
  if (!result.final_velocity_validation.empty()) {
    out << "final validation of the velocities\n"
        << TextVelocityTable(result.final_velocity_validation);
  }
  out << ZigzagRunsText(result.zigzags) << TurningRunsText(result.turning_circles);
  if (result.selection) out << "\n" << SelectionText(*result.selection);
  return out.str();
}

}  // namespace vesselid
