#include "engine/output/turning_report.h"

#include <cmath>
#include <cstdio>

#include "engine/base/format_numbers.h"
#include "engine/base/json_number.h"

namespace vesselid {
namespace {

constexpr double kRudderToDegrees = 180.0 / M_PI;

nlohmann::json FiguresToJson(const TurningFigures& f) {
  return {{"advance", JsonNumber(f.advance)},
          {"transfer", JsonNumber(f.transfer)},
          {"tactical_diameter", JsonNumber(f.tactical_diameter)},
          {"time_to_90_s", JsonNumber(f.time_to_90)},
          {"time_to_180_s", JsonNumber(f.time_to_180)}};
}

const char* Side(const TurningRun& run) { return run.test.sign > 0 ? "starboard" : "port"; }

}  // namespace

const char kTurningDefinitions[] =
    "IMO MSC.137(76): from the rudder execute, advance = distance along the original course "
    "where the heading has changed 90 deg, transfer = distance across it there, tactical "
    "diameter = distance across it where the heading has changed 180 deg. Simulated: the "
    "simulated track under the recorded rudder, from the same execute.";

double TurningErrorPercent(double measured, double simulated) {
  if (!std::isfinite(measured) || !std::isfinite(simulated) || measured == 0.0) {
    return std::nan("");
  }
  return 100.0 * (simulated - measured) / std::abs(measured);
}

nlohmann::json TurningRunsToJson(const std::vector<TurningRun>& runs) {
  nlohmann::json j = nlohmann::json::array();
  for (const TurningRun& run : runs) {
    const TurningFigures &m = run.measured, &s = run.simulated;
    j.push_back({{"stage", run.stage},
                 {"experiment", run.experiment},
                 {"held_out", run.held_out},
                 {"rudder_deg", std::abs(run.test.rudder) * kRudderToDegrees},
                 {"side", Side(run)},
                 {"execute_s", run.test.execute},
                 {"unit", run.unit},
                 {"measured", FiguresToJson(m)},
                 {"simulated", FiguresToJson(s)},
                 {"error_percent",
                  {{"advance", JsonNumber(TurningErrorPercent(m.advance, s.advance))},
                   {"transfer", JsonNumber(TurningErrorPercent(m.transfer, s.transfer))},
                   {"tactical_diameter",
                    JsonNumber(TurningErrorPercent(m.tactical_diameter, s.tactical_diameter))}}}});
  }
  return j;
}

std::string TurningRunsText(const std::vector<TurningRun>& runs) {
  if (runs.empty()) return "";
  const std::string unit = runs.front().unit.empty() ? "" : " " + runs.front().unit;
  std::string out = "\nturning circles, measured / simulated (error %) (" +
                    std::string(kTurningDefinitions) + ")\n";
  char line[400];
  std::snprintf(line, sizeof(line), "  %-12s %-16s %-9s %-14s %26s %26s %26s %15s %15s\n", "stage",
                "experiment", "data", "rudder", ("advance" + unit).c_str(),
                ("transfer" + unit).c_str(), ("tactical diameter" + unit).c_str(), "to 90 deg s",
                "to 180 deg s");
  out += line;
  for (const TurningRun& run : runs) {
    auto figure = [](double measured, double simulated) {
      const double error = TurningErrorPercent(measured, simulated);
      return FormatFinite("%.3g", measured) + " / " + FormatFinite("%.3g", simulated) + " (" +
             FormatFinite("%+.1f", error) + ")";
    };
    auto times = [](double measured, double simulated) {
      return FormatFinite("%.1f", measured) + " / " + FormatFinite("%.1f", simulated);
    };
    const std::string rudder =
        FormatFinite("%.1f", std::abs(run.test.rudder) * kRudderToDegrees) + " deg " + Side(run);
    std::snprintf(line, sizeof(line), "  %-12s %-16s %-9s %-14s %26s %26s %26s %15s %15s\n",
                  run.stage.c_str(), run.experiment.c_str(), run.held_out ? "held out" : "training",
                  rudder.c_str(), figure(run.measured.advance, run.simulated.advance).c_str(),
                  figure(run.measured.transfer, run.simulated.transfer).c_str(),
                  figure(run.measured.tactical_diameter, run.simulated.tactical_diameter).c_str(),
                  times(run.measured.time_to_90, run.simulated.time_to_90).c_str(),
                  times(run.measured.time_to_180, run.simulated.time_to_180).c_str());
    out += line;
  }
  return out;
}

}  // namespace vesselid
