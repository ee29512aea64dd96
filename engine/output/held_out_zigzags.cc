#include "engine/output/held_out_zigzags.h"

#include <cmath>
#include <cstdio>

#include "engine/base/student_t.h"

namespace vesselid {
namespace {

using nlohmann::json;

// Fewest training zigzags an interval is formed from (two degrees of freedom).
constexpr int kMinTrainingRuns = 3;

// The figure (first or second overshoot, deg) measured or simulated; NaN when unknown.
double FigureOf(const ZigzagEntry& z, bool measured, const std::string& figure) {
  const bool first = figure == "first_overshoot";
  return measured ? (first ? z.measured_first : z.measured_second)
                  : (first ? z.simulated_first : z.simulated_second);
}

}  // namespace

HeldOutZigzagCheck CheckHeldOutZigzags(const std::vector<ZigzagEntry>& zigzags) {
  HeldOutZigzagCheck check;
  // Held-out runs as the final values simulate them (else the last stage that has them);
  // training runs of the last stage that has them.
  std::string held_stage, training_stage;
  for (const ZigzagEntry& z : zigzags) {
    const std::string& stage = z.stage;
    if (z.held_out) {
      if (held_stage != "final") held_stage = stage;
    } else if (stage != "final") {
      training_stage = stage;
    }
  }
  if (held_stage.empty()) {
    check.note = "the run holds out no zigzag";
    return check;
  }
  check.stage = held_stage;
  for (const std::string figure : {"first_overshoot", "second_overshoot"}) {
    std::vector<double> errors;
    for (const ZigzagEntry& z : zigzags) {
      if (z.held_out || z.stage != training_stage) continue;
      const double e = FigureOf(z, true, figure) - FigureOf(z, false, figure);
      if (std::isfinite(e)) errors.push_back(e);
    }
    HeldOutZigzagCheck::Error error;
    error.figure = figure;
    error.runs = static_cast<int>(errors.size());
    if (error.runs < kMinTrainingRuns) {
      check.note += (check.note.empty() ? "" : "; ") + figure + ": " + std::to_string(error.runs) +
                    " training zigzags have it (fewer than " + std::to_string(kMinTrainingRuns) +
                    "): no interval";
      continue;
    }
    for (double e : errors) error.mean += e / error.runs;
    for (double e : errors) error.sd += (e - error.mean) * (e - error.mean) / (error.runs - 1);
    error.sd = std::sqrt(error.sd);
    error.t = StudentTQuantile(0.975, error.runs - 1);
    const double half = error.t * error.sd * std::sqrt(1.0 + 1.0 / error.runs);
    for (const ZigzagEntry& z : zigzags) {
      if (!z.held_out || z.stage != held_stage) continue;
      HeldOutZigzag row;
      row.experiment = z.experiment;
      char test[64];
      std::snprintf(test, sizeof(test), "%.1f/%.1f", z.rudder_deg, z.heading_deg);
      row.test = test;
      row.figure = figure;
      row.measured = FigureOf(z, true, figure);
      row.predicted = FigureOf(z, false, figure);
      if (!std::isfinite(row.measured) || !std::isfinite(row.predicted)) continue;
      row.low = row.predicted + error.mean - half;
      row.high = row.predicted + error.mean + half;
      row.covered = row.low <= row.measured && row.measured <= row.high;
      ++error.held_out;
      error.covered += row.covered ? 1 : 0;
      check.rows.push_back(row);
    }
    check.errors.push_back(error);
  }
  return check;
}

std::string HeldOutZigzagsText(const HeldOutZigzagCheck& check) {
  if (check.rows.empty() && check.note.empty()) return "";
  std::string text =
      "held-out zigzags, measured against predicted (95 % prediction interval "
      "from the training zigzags' errors)\n";
  char line[300];
  for (const HeldOutZigzagCheck::Error& e : check.errors) {
    std::snprintf(line, sizeof(line),
                  "  %s: error on %d training zigzags %+.3g +- %.3g deg (mean, SD), t = %.3f\n",
                  e.figure.c_str(), e.runs, e.mean, e.sd, e.t);
    text += line;
  }
  if (!check.rows.empty()) {
    std::snprintf(line, sizeof(line), "  %-12s %-11s %-17s %9s %10s %21s  %s\n", "experiment",
                  "test", "figure", "measured", "predicted", "interval", "covers");
    text += line;
  }
  for (const HeldOutZigzag& r : check.rows) {
    char interval[48];
    std::snprintf(interval, sizeof(interval), "[%.3g, %.3g]", r.low, r.high);
    std::snprintf(line, sizeof(line), "  %-12s %-11s %-17s %9.3g %10.3g %21s  %s\n",
                  r.experiment.c_str(), r.test.c_str(), r.figure.c_str(), r.measured, r.predicted,
                  interval, r.covered ? "yes" : "no");
    text += line;
  }
  for (const HeldOutZigzagCheck::Error& e : check.errors) {
    std::snprintf(line, sizeof(line), "  %s: the interval covers %d of %d held-out runs\n",
                  e.figure.c_str(), e.covered, e.held_out);
    text += line;
  }
  if (!check.note.empty()) text += "  note: " + check.note + "\n";
  return text;
}

json HeldOutZigzagsToJson(const HeldOutZigzagCheck& check) {
  json errors = json::array(), rows = json::array();
  for (const HeldOutZigzagCheck::Error& e : check.errors) {
    errors.push_back({{"figure", e.figure},
                      {"training_runs", e.runs},
                      {"mean_deg", e.mean},
                      {"sd_deg", e.sd},
                      {"t", e.t},
                      {"held_out_runs", e.held_out},
                      {"covered", e.covered}});
  }
  for (const HeldOutZigzag& r : check.rows) {
    rows.push_back({{"experiment", r.experiment},
                    {"test", r.test},
                    {"figure", r.figure},
                    {"measured_deg", r.measured},
                    {"predicted_deg", r.predicted},
                    {"interval_deg", {r.low, r.high}},
                    {"covered", r.covered}});
  }
  return {{"stage", check.stage}, {"errors", errors}, {"runs", rows}, {"note", check.note}};
}

}  // namespace vesselid
