// The fit of a list of experiments per run (configured record): one row per run, its
// segments folded in, and the mean, median and worst over the runs, for report.txt,
// report.html and results.json alike.
//
// Per run and output: samples; RMSE and MAE over all its samples; R^2 = 1 - sum SSE / sum SST
// and fit % = 100 (1 - sqrt(sum SSE / sum SST)), each segment's spread SST about its own
// mean (SST = SSE / (1 - R^2) of the segment). RMSE and MAE in the unit the user reads
// (display_units.h). Runs whose segments all diverged have no metrics; a diverged segment is
// counted and its message kept.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"

namespace vesselid {

// Beyond this many runs the rows are sorted worst first (lowest fit % of any output).
inline constexpr size_t kRunRowsInOrder = 12;

struct RunFitRow {
  std::string run;
  int segments = 0, diverged = 0;
  std::string diverged_message;  // of the first diverged segment
  // Per output of the table (RunFitTable::outputs); samples 0 where the run has none.
  std::vector<ChannelMetrics> channels;
  double rms_cost = std::numeric_limits<double>::quiet_NaN();   // over all its samples
  double worst_fit = std::numeric_limits<double>::quiet_NaN();  // lowest fit % of its outputs
};

// Mean, median or worst over the runs, per output (NaN where no run has the output).
struct RunFitSummary {
  std::string label;  // "mean", "median", "worst"
  std::vector<double> fit_percent, rmse;
  std::vector<std::string> run;  // worst only: the run it is
};

struct RunFitTable {
  std::vector<std::string> outputs, units;  // units as shown (display_units.h)
  std::vector<RunFitRow> rows;
  bool worst_first = false;            // more than kRunRowsInOrder rows: sorted worst first
  std::vector<RunFitSummary> summary;  // mean, median, worst (empty with fewer than 2 runs)
};

RunFitTable PerRunFits(const RunConfig& config, const std::vector<ExperimentFit>& fits);

// The table as report.txt prints it (each line indented by two spaces).
std::string RunFitTableText(const RunFitTable& table);

// Whether a fit is a simulation's (regression stages report RMS and R2 only, no MAE).
bool IsSimulationFit(const ExperimentFit& fit);

// The stage whose fit the summaries show: the last one whose estimates were kept and that
// simulated its runs (a run of it that diverged counts); null when none did.
const StageResult* LastAcceptedStage(const RunResult& result);

}  // namespace vesselid
