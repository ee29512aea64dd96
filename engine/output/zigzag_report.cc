#include "engine/output/zigzag_report.h"

#include <cmath>
#include <cstdio>

#include "engine/base/format_numbers.h"
#include "engine/base/json_number.h"
#include "engine/output/held_out_zigzags.h"

namespace vesselid {
namespace {

constexpr double kToDegrees = 180.0 / M_PI;

}  // namespace

const char kZigzagDefinitions[] =
    "IMO MSC.137(76): overshoot = largest heading change beyond psi_z after a rudder reversal "
    "(first: after the first reversal, second: after the second); time to the first check = "
    "first rudder execute to the heading change reaching psi_z; period = mean time between "
    "executes of the same sign. Simulated: the simulated heading under the recorded rudder, "
    "its executes where it reaches +-psi_z.";

namespace {

nlohmann::json FiguresToJson(const ZigzagFigures& f) {
  return {{"first_overshoot_deg", JsonNumber(f.first_overshoot * kToDegrees)},
          {"second_overshoot_deg", JsonNumber(f.second_overshoot * kToDegrees)},
          {"time_to_first_check_s", JsonNumber(f.time_to_first_check)},
          {"period_s", JsonNumber(f.period)},
          {"executes_s", f.executes}};
}

}  // namespace

std::string ZigzagTestLabel(const ZigzagRun& run) {
  return FormatFinite("%.1f", run.test.rudder * kToDegrees) + "/" +
         FormatFinite("%.1f", run.test.heading * kToDegrees);
}

nlohmann::json ZigzagRunsToJson(const std::vector<ZigzagRun>& runs) {
  nlohmann::json j = nlohmann::json::array();
  for (const ZigzagRun& run : runs) {
    nlohmann::json item = {{"stage", run.stage},
                           {"experiment", run.experiment},
                           {"held_out", run.held_out},
                           {"rudder_deg", run.test.rudder * kToDegrees},
                           {"heading_deg", run.test.heading * kToDegrees},
                           {"measured", FiguresToJson(run.measured)},
                           {"simulated", FiguresToJson(run.simulated)}};
    if (run.reflown_done) item["reflown"] = FiguresToJson(run.reflown);
    if (!run.reflown_why.empty()) item["reflown_why"] = run.reflown_why;
    j.push_back(std::move(item));
  }
  return j;
}

std::vector<ZigzagEntry> ZigzagEntries(const std::vector<ZigzagRun>& runs) {
  std::vector<ZigzagEntry> entries;
  // As results.json writes them: a figure that is not finite is unknown (null, NaN).
  auto deg = [](double radians) {
    const double value = radians * kToDegrees;
    return std::isfinite(value) ? value : ZigzagEntry::kNaN;
  };
  for (const ZigzagRun& run : runs) {
    ZigzagEntry e;
    e.stage = run.stage;
    e.experiment = run.experiment;
    e.held_out = run.held_out;
    e.rudder_deg = run.test.rudder * kToDegrees;
    e.heading_deg = run.test.heading * kToDegrees;
    e.measured_first = deg(run.measured.first_overshoot);
    e.measured_second = deg(run.measured.second_overshoot);
    e.simulated_first = deg(run.simulated.first_overshoot);
    e.simulated_second = deg(run.simulated.second_overshoot);
    entries.push_back(std::move(e));
  }
  return entries;
}

std::string ZigzagRunsText(const std::vector<ZigzagRun>& runs) {
  if (runs.empty()) return "";
  std::string out =
      "\nzigzag figures, measured / simulated (" + std::string(kZigzagDefinitions) +
      " Held-out runs are also re-flown in closed loop from their measured start, the rudder "
      "reversed at the model's own checks)\n";
  char line[320];
  std::snprintf(line, sizeof(line), "  %-12s %-20s %-9s %-11s %17s %17s %17s %17s\n", "stage",
                "experiment", "data", "test [deg]", "1st overshoot deg", "2nd overshoot deg",
                "to 1st check s", "period s");
  out += line;
  auto pair = [](double measured, double simulated, double scale, const char* format) {
    return FormatFinite(format, measured * scale) + " / " + FormatFinite(format, simulated * scale);
  };
  // One row: the measured figures against `other`'s.
  auto row = [&](const std::string& stage, const std::string& experiment, const char* data,
                 const std::string& test, const ZigzagFigures& measured,
                 const ZigzagFigures& other) {
    std::snprintf(
        line, sizeof(line), "  %-12s %-20s %-9s %-11s %17s %17s %17s %17s\n", stage.c_str(),
        experiment.c_str(), data, test.c_str(),
        pair(measured.first_overshoot, other.first_overshoot, kToDegrees, "%.2f").c_str(),
        pair(measured.second_overshoot, other.second_overshoot, kToDegrees, "%.2f").c_str(),
        pair(measured.time_to_first_check, other.time_to_first_check, 1.0, "%.1f").c_str(),
        pair(measured.period, other.period, 1.0, "%.1f").c_str());
    out += line;
  };
  for (const ZigzagRun& run : runs) {
    row(run.stage, run.experiment, run.held_out ? "held out" : "training", ZigzagTestLabel(run),
        run.measured, run.simulated);
    // Re-flown in closed loop (run/zigzag_reflight.h): measured / re-flown.
    if (run.reflown_done) {
      row("", "  re-flown", "", "", run.measured, run.reflown);
    } else if (!run.reflown_why.empty()) {
      out += "  " + std::string(34, ' ') + "  not re-flown: " + run.reflown_why + "\n";
    }
  }
  // The held-out runs against their prediction intervals (held_out_zigzags.h).
  const HeldOutZigzagCheck check = CheckHeldOutZigzags(ZigzagEntries(runs));
  if (!check.rows.empty()) out += "\n" + HeldOutZigzagsText(check);
  return out;
}

}  // namespace vesselid
