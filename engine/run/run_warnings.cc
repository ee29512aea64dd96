#include "engine/run/run_warnings.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "engine/run/bootstrap_uncertainty.h"
#include "engine/run/bootstrap_warnings.h"
#include "engine/run/compensation_warnings.h"
#include "engine/run/input_noise_notes.h"
#include "engine/run/residual_warnings.h"

namespace vesselid {
namespace {

// Per output, the experiments whose fit failed there.
void FailedFits(const std::string& where, const std::vector<ExperimentFit>& fits,
                std::vector<std::string>* warnings) {
  std::map<std::string, std::vector<std::string>> failed;
  std::map<std::string, int> compared;
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) {
      ++compared[m.output];
      if (FitFailed(m)) failed[m.output].push_back(fit.experiment);
    }
  }
  for (const auto& [output, experiments] : failed) {
    std::string names;
    for (size_t i = 0; i < experiments.size() && i < 8; ++i) {
      names += (i > 0 ? ", " : "") + experiments[i];
    }
    if (experiments.size() > 8) names += ", ...";
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the fit of %s failed in %zu of %d experiment(s) (R2 < 0 or RMSE above %g "
                  "times the data's noise level): ",
                  output.c_str(), experiments.size(), compared[output], kFailedFitNoiseRatio);
    warnings->push_back(where + text + names);
  }
}

// Stage notes that are warnings: active bounds, held-out divergences, a noise model that
// did not settle or could not be estimated, global-start points that diverged.
bool WarningNote(const std::string& note) {
  return note.rfind("integration step", 0) == 0 || note.rfind("outliers:", 0) == 0 ||
         note.rfind(kNarrowHessianNote, 0) == 0 || note.rfind(kBootstrapNote, 0) == 0 ||
         note.rfind("noise weights:", 0) == 0 || note.rfind(kInputNoiseIntervalNote, 0) == 0 ||
         note.rfind("global start: ", 0) == 0 ||  // points whose simulation diverged
         note.find(" is at its lower bound") != std::string::npos ||
         note.find(" is at its upper bound") != std::string::npos ||
         note.find("diverges") != std::string::npos;
}

}  // namespace

bool FinalHeldOutFailed(const RunResult& run, std::vector<std::string>* reasons) {
  std::map<std::string, std::pair<double, double>> error_sum;  // output: (sum MAE n, hold)
  int diverged = 0;
  for (const ExperimentFit& fit : run.final_validation) {
    if (fit.diverged) {
      ++diverged;
      if (reasons != nullptr) reasons->push_back("final validation: " + fit.message);
      continue;
    }
    for (const ChannelMetrics& m : fit.channels) {
      error_sum[m.output].first += m.mae * m.samples;
      error_sum[m.output].second += m.hold_mae * m.samples;
    }
  }
  bool failed = diverged > 0;
  for (const auto& [output, sums] : error_sum) {
    if (!(sums.first > sums.second)) continue;
    failed = true;
    if (reasons == nullptr) continue;
    char text[256];
    std::snprintf(text, sizeof(text),
                  "final validation: the simulated %s predicts the held-out data worse than "
                  "holding its first measured value (pooled MAE ratio %.3g)",
                  output.c_str(), sums.first / sums.second);
    reasons->push_back(text);
  }
  return failed;
}

void AddRunWarnings(const RunConfig& config, RunResult* run) {
  std::vector<std::string>& w = run->warnings;
  if (!run->stopped_stage.empty()) {
    w.push_back("the run stopped in stage '" + run->stopped_stage + "' after " +
                std::to_string(run->stages.size()) + " of " + std::to_string(config.stages.size()) +
                " stage(s); the results are those of the finished stages: " + run->stop_message);
  }
  for (const StageResult& stage : run->stages) {
    const std::string where = "stage '" + stage.name + "': ";
    if (!stage.rejected.empty()) w.push_back(where + stage.rejected);
    if (stage.held_out.worse && stage.rejected.empty()) {
      w.push_back(where + "worse on held-out data than its start (" +
                  DescribeHeldOut(stage.held_out) + "), kept because of final: last");
    }
    if (!stage.held_out.worse) {
      for (size_t i = 0; i < stage.held_out.outputs.size(); ++i) {
        if (stage.held_out.stage_mae[i] > kHeldOutTolerance * stage.held_out.start_mae[i]) {
          char text[200];
          std::snprintf(text, sizeof(text),
                        "predicts the held-out %s worse than its start (MAE %.4g -> %.4g), though "
                        "better over all outputs",
                        stage.held_out.outputs[i].c_str(), stage.held_out.start_mae[i],
                        stage.held_out.stage_mae[i]);
          w.push_back(where + text);
        }
      }
    }
    for (const std::string& note : stage.summary.notes) {
      if (WarningNote(note)) w.push_back(where + note + StructureHint(config.model->info(), note));
    }
    AddCompensationWarnings(config.model->info(), stage, where, &w);
    AddBootstrapWarnings(stage, where, &w);
    for (const std::string& a : stage.admissibility) w.push_back(where + "not admissible: " + a);
    if (stage.summary.usable && stage.summary.chosen >= 0 &&
        stage.summary.local().termination == "NO_CONVERGENCE") {
      w.push_back(where + "the solver stopped after " +
                  std::to_string(stage.summary.local().iterations) +
                  " iterations without converging (local.max_iterations): the estimate may not "
                  "be an optimum");
    }
    FailedFits(where, stage.summary.fits, &w);
    AddResidualWarnings(stage, &w);
  }
  for (const std::string& a : run->admissibility) w.push_back("final values not admissible: " + a);
  FinalHeldOutFailed(*run, &w);
}

}  // namespace vesselid
