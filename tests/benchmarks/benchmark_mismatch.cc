// The shipped input-gain configs on a campaign whose structure is not the model's (the
// quadratic-thrust USV of problems/input_gain/quadratic_usv.h, 110 segments of 20-40 s), and
// on a copy with real-log defects (a segment that starts mid-manoeuvre, one GNSS fix 12 m
// off), beside a plain OLS on Savitzky-Golay velocities (reference_ols_input_gain.py): per
// stage the held-out MAE against its start, what the run kept and warned, the final free-run
// R2 of u, v, r, and the wall times.
//
//   build/tests/benchmarks/benchmark_mismatch [static|dynamic|both]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "nlohmann/json.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kPython = "/usr/bin/python3";  // Debian's, with python3-scipy

double Timed(const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return status == 0 ? seconds : -seconds;
}

// The shipped config with its simulation section replaced.
std::string MismatchConfig(const std::string& kind, bool defects) {
  std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/configs/input_gain_" + kind + ".yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  // The simulation section ends where the experiments (or their defaults) begin.
  const size_t begin = config.find("simulation:"), end = config.find("\nexperiment") + 1;
  std::string simulation =
      "simulation:\n  file: campaign.csv\n  vessel: quadratic_usv\n  segments: 110\n"
      "  segment_s: [20, 40]\n  duration_min: 55\n  seed: 3\n"
      "  noise: {position: 0.02, heading_deg: 0.3}\n";
  if (defects) simulation += "  defects: {abrupt_start_segment: 7, glitch_segment: 20}\n";
  return config.substr(0, begin) + simulation + "\n" + config.substr(end);
}

// "name@<id>" experiments of a stage's fit or validation metrics.
std::string Ids(const json& metrics, const std::string& prefix) {
  std::set<int> ids;
  for (const json& m : metrics) {
    const std::string name = m["experiment"];
    if (name.rfind(prefix + "@", 0) == 0) ids.insert(std::stoi(name.substr(prefix.size() + 1)));
  }
  std::string list;
  for (int id : ids) list += (list.empty() ? "" : ",") + std::to_string(id);
  return list;
}

void Report(const std::string& label, const fs::path& dir, double seconds) {
  std::ifstream in(dir / "out" / "results.json");
  const json r = json::parse(in, nullptr, false);
  std::printf("\n%s: %s, %.0f s\n", label.c_str(), seconds >= 0 ? "exit 0" : "exit 1",
              std::abs(seconds));
  if (r.is_discarded()) {
    std::printf("  no results.json\n");
    return;
  }
  for (const json& s : r["stages"]) {
    std::printf("  stage %-14s", s["name"].get<std::string>().c_str());
    if (s.contains("held_out_check")) {
      for (const json& o : s["held_out_check"]["outputs"]) {
        std::printf(" %s %.4g->%.4g", o["output"].get<std::string>().c_str(),
                    o["start_mae"].get<double>(), o["stage_mae"].get<double>());
      }
      std::printf("%s", s["held_out_check"]["worse"].get<bool>() ? "  WORSE" : "");
    }
    std::printf("%s\n", s.contains("rejected") ? "  (set aside)" : "");
  }
  std::printf("  final free-run R2 (held-out, vs the simulator's true velocities):");
  for (const json& m : r["final_velocity_validation"]) {
    if (m["prediction"].get<std::string>().find("free-run") == std::string::npos) continue;
    std::printf(" %s %.3f", m["state"].get<std::string>().c_str(), m["r2"].get<double>());
  }
  std::printf("\n  verdict: %s, run findings: %zu\n", r["verdict"].get<std::string>().c_str(),
              r["findings"].size());
  for (const json& f : r["findings"]) {
    std::printf("    %s [%s] %s\n", f["severity"].get<std::string>().c_str(),
                f["kind"].get<std::string>().c_str(),
                f["message"].get<std::string>().substr(0, 200).c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "both";
  const fs::path root = fs::temp_directory_path() / "vesselid_benchmark_mismatch";
  fs::remove_all(root);
  const std::string binary = VESSELID_BINARY;
  bool reference_done = false;
  for (const std::string kind : {"static", "dynamic"}) {
    if (which != "both" && which != kind) continue;
    for (bool defects : {false, true}) {
      const fs::path dir = root / (kind + (defects ? "_defects" : ""));
      fs::create_directories(dir);
      std::ofstream(dir / "config.yaml") << MismatchConfig(kind, defects);
      if (Timed(binary + " simulate " + (dir / "config.yaml").string() + " --out " + dir.string() +
                " > /dev/null") < 0) {
        return 1;
      }
      const double seconds = Timed(binary + " run " + (dir / "config.yaml").string() + " --data " +
                                   dir.string() + " --out " + (dir / "out").string() +
                                   " --quiet > /dev/null 2> " + (dir / "stderr").string());
      Report(kind + (defects ? ", with log defects" : ""), dir, seconds);
      if (reference_done || defects) continue;
      std::ifstream in(dir / "out" / "results.json");
      const json r = json::parse(in, nullptr, false);
      if (r.is_discarded() || r["stages"].empty()) continue;
      const json& first = r["stages"][0];
      const std::string held = Ids(first["validation"]["metrics"], "validation");
      const std::string training = Ids(r["stages"].back()["fit"]["metrics"], "training");
      const fs::path out = dir / "ols.json";
      const double ols =
          Timed(std::string(kPython) + " " + VESSELID_SOURCE_DIR +
                "/tests/benchmarks/reference_ols_input_gain.py " + (dir / "campaign.csv").string() +
                " " + held + " " + training + " > " + out.string());
      std::ifstream ols_in(out);
      const json o = json::parse(ols_in, nullptr, false);
      if (ols < 0 || o.is_discarded()) {
        std::printf("  OLS reference failed\n");
        continue;
      }
      std::printf("\nOLS on Savitzky-Golay velocities (SciPy), same held-out segments, %.1f s:\n",
                  ols);
      std::printf(
          "  free-run R2 vs the SG reconstruction: u %.3f v %.3f r %.3f (vs the truth: "
          "u %.3f v %.3f r %.3f), %d diverged\n",
          o["u"]["r2"].get<double>(), o["v"]["r2"].get<double>(), o["r"]["r2"].get<double>(),
          o["u"]["r2_truth"].get<double>(), o["v"]["r2_truth"].get<double>(),
          o["r"]["r2_truth"].get<double>(), o["diverged"].get<int>());
      reference_done = true;
    }
  }
  return 0;
}
