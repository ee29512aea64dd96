// Surge-sway-yaw fits of spirals of several turns from random starts, the engine against a
// plain SciPy least-squares fit on the same data (reference_3dof.py, an implementation of
// MODELS.md section 1 written from the spec, also the data's simulator): how many of the
// fixed starts reach the optimum, and at what time: with headings compared unwrapped (the
// default) and modulo one turn (`wrap: [psi]`), with the far-start recipe, and with the
// multistart global start (`global: {seed: 1}`).
//
//   build/tests/benchmarks/benchmark_spirals [starts] [variant]  (default 11 starts, +-30 %;
//       variant: plain, wrapped, continuation or global; default all)
//
// Each start's outcome is printed as it ends (a campaign takes minutes per start).
// VESSELID_BENCHMARK_BINARY runs another vesselid binary (e.g. a copy, while the build tree
// changes).
//
// A start succeeds when every parameter ends within 1 % of the value the same tool reaches
// from the true values (run first, not counted; a floor of 1e-4 of the parameter's bound range
// for a value near 0, Yr). Scored by the parameters, never by the cost the engine reports:
// under `weights: noise` that is ~N/2 at any end point. Each start's comparable cost (the
// residuals under the configured weights, results.json's comparable_cost) is printed beside.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

#include "nlohmann/json.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<std::pair<std::string, double>> kTruth = {
    {"Iz", 0.80},    {"Xudot", -1.0946}, {"Yvdot", -1.0536}, {"Yrdot", -1.4353},
    {"Xu", -5.6128}, {"Yv", -3.5059},    {"Yr", -0.0001},    {"Nv", -1.0005},
    {"Nr", -0.1039}, {"Xuu", -2.3136},   {"Yvv", -3.9310},   {"Nrr", -0.2605}};
const std::map<std::string, std::pair<double, double>> kBounds = {
    {"Iz", {0.01, 10}}, {"Xudot", {-10, 5}}, {"Yvdot", {-10, 5}}, {"Yrdot", {-10, 5}},
    {"Xu", {-60, 0}},   {"Yv", {-40, 0}},    {"Yr", {-1, 1}},     {"Nv", {-10, 0}},
    {"Nr", {-2, 0}},    {"Xuu", {-30, 0}},   {"Yvv", {-40, 0}},   {"Nrr", {-3, 0}}};
constexpr int kRuns = 5;
const char* kPython = "/usr/bin/python3";  // Debian's, with python3-scipy

double Timed(const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  if (std::system(command.c_str()) != 0) return -1.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every parameter within 1 % of the reference end point (floor: 1e-4 of its bound range).
bool Success(const std::map<std::string, double>& estimate,
             const std::map<std::string, double>& reference, std::string* worst = nullptr) {
  if (estimate.size() != reference.size()) return false;
  bool ok = true;
  double largest = 0.0;
  for (const auto& [name, value] : reference) {
    const auto found = estimate.find(name);
    if (found == estimate.end()) return false;
    const auto& [lower, upper] = kBounds.at(name);
    const double tolerance = 0.01 * std::max(std::abs(value), 0.01 * (upper - lower));
    const double miss = std::abs(found->second - value) / tolerance;
    ok = ok && miss <= 1.0;
    if (worst != nullptr && miss > largest) {
      largest = miss;
      char text[96];
      std::snprintf(text, sizeof(text), "%s %.4g (optimum %.4g)", name.c_str(), found->second,
                    value);
      *worst = text;
    }
  }
  return ok;
}

// The final parameters of a results.json (empty when it is missing).
std::map<std::string, double> Estimate(const json& results) {
  std::map<std::string, double> values;
  if (results.is_discarded() || !results.contains("parameters")) return values;
  for (const json& p : results["parameters"]) {
    if (kBounds.count(p["name"].get<std::string>()) > 0) {
      values[p["name"].get<std::string>()] = p["value"].get<double>();
    }
  }
  return values;
}

// How the engine is asked: as the SciPy script fits (whole runs), with the heading wrapped
// (today's behaviour before unwrapping), and with the far-start recipe (continuation on 10 s,
// then 30 s pieces, each piece's velocities free).
enum class Variant { kPlain, kWrapped, kContinuation, kGlobal };

std::string Config(const std::map<std::string, double>& start, Variant variant) {
  const bool wrap = variant == Variant::kWrapped;
  std::string text =
      "model: {family: erunsal6dof, active_dofs: [surge, sway, yaw]}\nexperiments:\n";
  for (int k = 0; k < kRuns; ++k) {
    const std::string run = "run" + std::to_string(k);
    text += "  - {name: " + run + ", file: " + run +
            ".csv, inputs: {c_L: c_L, c_R: c_R}, outputs: {x: x, y: y, psi: psi}, "
            "interpolation: zero_order_hold" +
            std::string(wrap ? ", wrap: [psi]" : "") + "}\n";
  }
  text += "stages:\n  - name: fit\n    integration: {max_step: 0.02}\n";
  if (variant == Variant::kContinuation) {
    text += "    continuation: [10, 30]\n    free_initial_states: [u, v, r]\n";
  }
  if (variant == Variant::kGlobal) text += "    global: {seed: 1}\n";
  text += "    parameters:\n";
  for (const auto& [name, value] : start) {
    const auto& [lower, upper] = kBounds.at(name);
    text += "      " + name + ": {start: " + std::to_string(value) +
            ", lower: " + std::to_string(lower) + ", upper: " + std::to_string(upper) + "}\n";
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 11;
  const std::string only = argc > 2 ? argv[2] : "";
  const fs::path dir = fs::temp_directory_path() /
                      ("vesselid_benchmark_spirals_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string script =
      std::string(VESSELID_SOURCE_DIR) + "/tests/benchmarks/reference_3dof.py";
  if (Timed(std::string(kPython) + " " + script + " simulate " + dir.string() + " 2> " +
            (dir / "simulate.log").string()) < 0) {
    std::fprintf(stderr, "the reference simulation failed (is python3-scipy installed?)\n");
    return 1;
  }
  std::mt19937 random(11);
  std::uniform_real_distribution<double> factor(0.7, 1.3);
  // Start 0 is the truth: the reference cost of each tool.
  std::vector<std::map<std::string, double>> starts(count + 1);
  json starts_json = json::array();
  for (size_t i = 0; i < starts.size(); ++i) {
    for (const auto& [name, truth] : kTruth)
      starts[i][name] = truth * (i == 0 ? 1.0 : factor(random));
    starts_json.push_back(starts[i]);
  }
  std::ofstream(dir / "starts.json") << starts_json.dump();

  std::printf(
      "surge-sway-yaw fit of %d spiral/zigzag runs, %d starts within +-30 %% of the truth\n", kRuns,
      count);
  std::printf("  %-34s %10s %12s\n", "", "successes", "time/start");
  const std::tuple<Variant, const char*, const char*> variants[] = {
      {Variant::kPlain, "plain", "vesselid, heading unwrapped"},
      {Variant::kWrapped, "wrapped", "vesselid, heading wrapped (wrap:)"},
      {Variant::kContinuation, "continuation", "vesselid, unwrapped, continuation"},
      {Variant::kGlobal, "global", "vesselid, unwrapped, multistart"}};
  for (const auto& [variant, name, label] : variants) {
    if (!only.empty() && only != name) continue;
    int successes = 0;
    double seconds = 0.0;
    std::map<std::string, double> reference;
    for (int i = 0; i <= count; ++i) {
      const fs::path config = dir / ("start" + std::to_string(i) + ".yaml");
      const fs::path out = dir / ("out" + std::to_string(i));
      std::ofstream(config) << Config(starts[i], variant);
      const char* binary = std::getenv("VESSELID_BENCHMARK_BINARY");
      const double t = Timed(std::string(binary != nullptr ? binary : VESSELID_BINARY) + " run " +
                             config.string() + " --out " + out.string() +
                             " --quiet > /dev/null 2>&1");
      std::ifstream in(out / "results.json");
      const json results = json::parse(in, nullptr, false);
      const double cost = results.is_discarded() || !results["stages"][0]["comparable_cost"].is_number()
                              ? INFINITY
                              : results["stages"][0]["comparable_cost"].get<double>();
      const std::map<std::string, double> estimate = Estimate(results);
      std::string worst;
      const bool success = i > 0 && Success(estimate, reference, &worst);
      std::fprintf(stderr, "  %s start %d: comparable cost %.6e, verdict %s, %.1f s%s\n", name, i,
                   cost, results.is_discarded() ? "none" : results["verdict"].get<std::string>().c_str(), t,
                   i == 0 ? " (from the truth: the reference)"
                          : (success ? " (optimum)" : (" (missed: " + worst + ")").c_str()));
      if (i == 0) {
        reference = estimate;
        continue;
      }
      seconds += std::max(0.0, t);
      successes += success;
    }
    std::printf("  %-34s %7d/%-2d %10.1f s\n", label, successes, count, seconds / count);
  }
  if (!only.empty()) {  // one engine variant asked for: no SciPy fit
    fs::remove_all(dir);
    return 0;
  }
  const fs::path fits = dir / "scipy.json";
  const double scipy_time = Timed(std::string(kPython) + " " + script + " fit " + dir.string() +
                                  " " + (dir / "starts.json").string() + " > " + fits.string());
  std::ifstream in(fits);
  const json reference = json::parse(in, nullptr, false);
  if (scipy_time < 0 || reference.is_discarded()) {
    std::fprintf(stderr, "the SciPy fit failed\n");
    return 1;
  }
  int successes = 0;
  double fit_seconds = 0.0;
  std::map<std::string, double> optimum;
  for (size_t i = 0; i < reference["results"].size(); ++i) {
    const json& r = reference["results"][i];
    std::map<std::string, double> estimate;
    for (const auto& [name, value] : r["estimate"].items()) estimate[name] = value.get<double>();
    if (i == 0) {
      optimum = estimate;
      continue;
    }
    fit_seconds += r["seconds"].get<double>();
    successes += Success(estimate, optimum);
  }
  std::printf("  %-34s %7d/%-2d %10.1f s  (%.0f s of Python in all)\n", "SciPy least_squares (trf)",
              successes, count, fit_seconds / count, scipy_time);
  fs::remove_all(dir);
  return 0;
}
