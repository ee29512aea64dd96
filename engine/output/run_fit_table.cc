#include "engine/output/run_fit_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "engine/base/format_numbers.h"
#include "engine/base/nan.h"
#include "engine/base/statistics.h"
#include "engine/run/display_units.h"

namespace vesselid {
namespace {

// Sums of one run and output over its segments.
struct ChannelSums {
  int samples = 0;
  double sse = 0.0, sae = 0.0, sst = 0.0, hold_sae = 0.0;
  bool spread_known = false;
};

}  // namespace

RunFitTable PerRunFits(const RunConfig& config, const std::vector<ExperimentFit>& fits) {
  RunFitTable table;
  std::map<std::string, size_t> row_of;
  std::vector<std::vector<ChannelSums>> sums;
  std::vector<double> cost2, cost_samples;
  for (const ExperimentFit& fit : fits) {
    const std::string run = RecordName(fit.experiment);
    const auto [at, added] = row_of.emplace(run, table.rows.size());
    if (added) {
      table.rows.emplace_back();
      table.rows.back().run = run;
      sums.emplace_back();
      cost2.push_back(0.0);
      cost_samples.push_back(0.0);
    }
    const size_t r = at->second;
    RunFitRow& row = table.rows[r];
    ++row.segments;
    if (fit.diverged) {
      if (row.diverged++ == 0) row.diverged_message = fit.message;
      continue;
    }
    int samples = 0;
    for (const ChannelMetrics& m : fit.channels) {
      auto known = std::find(table.outputs.begin(), table.outputs.end(), m.output);
      if (known == table.outputs.end()) {
        table.outputs.push_back(m.output);
        known = table.outputs.end() - 1;
      }
      const size_t o = known - table.outputs.begin();
      if (sums[r].size() <= o) sums[r].resize(o + 1);
      ChannelSums& s = sums[r][o];
      const double sse = m.rmse * m.rmse * m.samples;
      s.samples += m.samples;
      s.sse += sse;
      s.sae += m.mae * m.samples;
      if (std::isfinite(m.hold_mae)) s.hold_sae += m.hold_mae * m.samples;
      if (std::isfinite(m.r2) && m.r2 < 1.0) {
        s.sst += sse / (1.0 - m.r2);
        s.spread_known = true;
      }
      samples += m.samples;
    }
    if (std::isfinite(fit.rms_cost)) {
      cost2[r] += fit.rms_cost * fit.rms_cost * samples;
      cost_samples[r] += samples;
    }
  }
  // Units per output: the first run's (a degrees column in one record, radians in another is
  // unusual; each row converts with its own run's unit, named in the header by the first).
  for (const std::string& output : table.outputs) {
    table.units.push_back(
        OutputDisplayUnit(config, table.rows.empty() ? "" : table.rows.front().run, output).unit);
  }
  for (size_t r = 0; r < table.rows.size(); ++r) {
    RunFitRow& row = table.rows[r];
    sums[r].resize(table.outputs.size());
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      const ChannelSums& s = sums[r][o];
      ChannelMetrics m;
      m.experiment = row.run;
      m.output = table.outputs[o];
      m.samples = s.samples;
      if (s.samples == 0) {
        m.rmse = m.mae = m.r2 = m.fit_percent = kNaN;
      } else {
        const double scale = OutputDisplayUnit(config, row.run, m.output).scale;
        m.rmse = scale * std::sqrt(s.sse / s.samples);
        m.mae = scale * s.sae / s.samples;
        m.hold_mae = scale * s.hold_sae / s.samples;
        m.r2 = s.spread_known && s.sst > 0 ? 1.0 - s.sse / s.sst : kNaN;
        m.fit_percent =
            s.spread_known && s.sst > 0 ? 100.0 * (1.0 - std::sqrt(s.sse / s.sst)) : kNaN;
        if (std::isfinite(m.fit_percent) &&
            !(row.worst_fit <= m.fit_percent)) {  // NaN start: the first one
          row.worst_fit = m.fit_percent;
        }
      }
      row.channels.push_back(m);
    }
    if (cost_samples[r] > 0) row.rms_cost = std::sqrt(cost2[r] / cost_samples[r]);
  }
  if (table.rows.size() > kRunRowsInOrder) {
    table.worst_first = true;
    // Diverged runs first, then by the lowest fit %; runs without a fit % last.
    auto key = [](const RunFitRow& row) {
      if (row.diverged > 0) return -std::numeric_limits<double>::infinity();
      return std::isfinite(row.worst_fit) ? row.worst_fit : std::numeric_limits<double>::infinity();
    };
    std::stable_sort(table.rows.begin(), table.rows.end(),
                     [&](const RunFitRow& a, const RunFitRow& b) { return key(a) < key(b); });
  }
  if (table.rows.size() >= 2) {
    RunFitSummary mean, median, worst;
    mean.label = "mean";
    median.label = "median";
    worst.label = "worst";
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      std::vector<double> fit, rmse;
      const RunFitRow* worst_row = nullptr;
      for (const RunFitRow& row : table.rows) {
        const ChannelMetrics& m = row.channels[o];
        if (std::isfinite(m.fit_percent)) {
          fit.push_back(m.fit_percent);
          if (worst_row == nullptr || m.fit_percent < worst_row->channels[o].fit_percent) {
            worst_row = &row;
          }
        }
        if (std::isfinite(m.rmse)) rmse.push_back(m.rmse);
      }
      double fit_sum = 0.0, rmse_sum = 0.0;
      for (double f : fit) fit_sum += f;
      for (double e : rmse) rmse_sum += e;
      mean.fit_percent.push_back(fit.empty() ? kNaN : fit_sum / fit.size());
      mean.rmse.push_back(rmse.empty() ? kNaN : rmse_sum / rmse.size());
      median.fit_percent.push_back(Median(fit));
      median.rmse.push_back(Median(rmse));
      worst.fit_percent.push_back(worst_row ? worst_row->channels[o].fit_percent : kNaN);
      worst.rmse.push_back(worst_row ? worst_row->channels[o].rmse : kNaN);
      worst.run.push_back(worst_row ? worst_row->run : "");
      mean.run.push_back("");
      median.run.push_back("");
    }
    table.summary = {mean, median, worst};
  }
  return table;
}

std::string RunFitTableText(const RunFitTable& table) {
  std::string out;
  char cell[160];
  std::snprintf(cell, sizeof(cell), "  %-24s %8s", "run", "segments");
  out += cell;
  for (size_t o = 0; o < table.outputs.size(); ++o) {
    std::snprintf(
        cell, sizeof(cell), " %10s %14s", ("fit % " + table.outputs[o]).c_str(),
        ("RMSE " + table.outputs[o] + (table.units[o].empty() ? "" : " [" + table.units[o] + "]"))
            .c_str());
    out += cell;
  }
  std::snprintf(cell, sizeof(cell), " %12s\n", "rms cost");
  out += cell;
  for (const RunFitRow& row : table.rows) {
    const std::string segments = row.diverged > 0 ? std::to_string(row.segments) + " (" +
                                                        std::to_string(row.diverged) + " div.)"
                                                  : std::to_string(row.segments);
    std::snprintf(cell, sizeof(cell), "  %-24s %8s", row.run.c_str(), segments.c_str());
    out += cell;
    for (const ChannelMetrics& m : row.channels) {
      std::snprintf(cell, sizeof(cell), " %10s %14s", FormatFinite("%.2f", m.fit_percent).c_str(),
                    FormatFinite("%.4g", m.rmse).c_str());
      out += cell;
    }
    std::snprintf(cell, sizeof(cell), " %12s\n", FormatFinite("%.4e", row.rms_cost).c_str());
    out += cell;
  }
  for (const RunFitSummary& s : table.summary) {
    std::string label = s.label + " of " + std::to_string(table.rows.size()) + " runs";
    std::snprintf(cell, sizeof(cell), "  %-33s", label.c_str());
    out += cell;
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      std::snprintf(cell, sizeof(cell), " %10s %14s",
                    FormatFinite("%.2f", s.fit_percent[o]).c_str(),
                    FormatFinite("%.4g", s.rmse[o]).c_str());
      out += cell;
    }
    out += "\n";
    if (s.label == "worst") {
      for (size_t o = 0; o < table.outputs.size(); ++o) {
        if (!s.run[o].empty()) out += "    worst " + table.outputs[o] + ": " + s.run[o] + "\n";
      }
    }
  }
  for (const RunFitRow& row : table.rows) {
    if (row.diverged > 0) out += "  " + row.run + ": " + row.diverged_message + "\n";
  }
  if (table.worst_first) out += "  (runs sorted worst first: lowest fit % of any output)\n";
  return out;
}

bool IsSimulationFit(const ExperimentFit& fit) {
  for (const ChannelMetrics& m : fit.channels) {
    if (m.samples > 0 && std::isfinite(m.mae)) return true;
  }
  return false;
}

const StageResult* LastAcceptedStage(const RunResult& result) {
  for (auto it = result.stages.rbegin(); it != result.stages.rend(); ++it) {
    if (!it->rejected.empty()) continue;
    for (const ExperimentFit& fit : it->summary.fits) {
      if (IsSimulationFit(fit) || fit.diverged) return &*it;
    }
  }
  return nullptr;
}

}  // namespace vesselid
