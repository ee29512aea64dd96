// The filter-error method as the command line runs it (stage key `noise:`, docs/models.md
// "Disturbance models"), on the patrol vessel's multi-sine record whose logged rudder carries
// 0.1 deg of noise: output error's heading residuals are then coloured (the rudder's noise
// integrated; residual_whiteness_test.cc). With process noise on the rudder's equation the
// filter's innovations are white, the run names the disturbance (disturbance_model), reports
// its parameters as estimates of kind noise and is not called doubtful for the colour. `auto`
// picks a disturbance model by BIC and names every candidate. Keys: noise, method, angles,
// measurement (white, ar1: type, sigma, tau, white), process, wave (omega, zeta, sigma), bias
// (q, initial_sd), prediction_steps, gain.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/findings.h"

namespace vesselid {
namespace filter_error_run_test {

namespace fs = std::filesystem;
using nlohmann::json;

// `held_out`: a second, shorter record the stage predicts (its validation).
std::string Config(const std::string& noise, bool held_out = false) {
  const std::string check_record = held_out ? R"(
    - file: check.csv
      duration: 120
      excitation: {type: multisine, amplitude_deg: 20, periods: [60, 30, 15, 7.5, 4]}
      noise: {rudder_deg: 0.1, heading_deg: 0.1}
      seed: 13)"
                                            : "";
  const std::string check_experiment = held_out ? R"(
  - name: check
    file: check.csv
    inputs: {delta: delta}
    outputs: {psi: psi})"
                                                : "";
  return R"(description: patrol vessel, multi-sine, noisy rudder
model: {family: nomoto, type: second_order}
simulation:
  truth: {T1: 2.0875, T2: 0.3179, T3: 0.1830, K: -0.1724}
  steering_gear: {Tm: 1.0, kp: 0.7, rudder_limit_deg: 35}
  sample_time: 0.1
  experiments:
    - file: multisine.csv
      duration: 600
      excitation: {type: multisine, amplitude_deg: 20, periods: [60, 30, 15, 7.5, 4]}
      noise: {rudder_deg: 0.1, heading_deg: 0.1}
      seed: 12)" + check_record + R"(
experiments:
  - name: multisine
    file: multisine.csv
    inputs: {delta: delta}
    outputs: {psi: psi})" + check_experiment + R"(
stages:
  - name: multisine
    experiments: [multisine])" + (held_out ? "\n    validation: [check]" : "") + R"(
    parameters:
      T1: {start: 2.5, lower: 0.01, upper: 20.0}
      T2: {start: 0.26, lower: 0.01, upper: 20.0}
      T3: {start: 0.22, lower: 0.0, upper: 5.0}
      K: {start: -0.2, lower: -2.0, upper: -0.001}
    noise: )" + noise + "\n";
}

struct CommandRun {
  int status = -1;
  json results;
  std::string report, stderr_text;
  json predictions;  // `vesselid predict`'s predictions.json, where asked
  // results.json of the same run again with --resume (every stage from its checkpoint),
  // where asked.
  json resumed;
};

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Simulates the records of `config_text` and runs it (then predicts, if asked).
CommandRun SimulateAndRunConfig(const std::string& name, const std::string& config_text,
                                bool predict = false, bool resume = false) {
  const fs::path dir = fs::temp_directory_path() / ("vesselid_filter_error_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path config = dir / "config.yaml";
  std::ofstream(config) << config_text;
  const std::string binary = VESSELID_BINARY;
  const std::string simulate =
      binary + " simulate " + config.string() + " --out " + dir.string() + " > /dev/null";
  const std::string run = binary + " run " + config.string() + " --data " + dir.string() +
                          " --out " + (dir / "out").string() + " --quiet --no-report > /dev/null 2> " +
                          (dir / "stderr.txt").string();
  CommandRun result;
  EXPECT_EQ(std::system(simulate.c_str()), 0) << simulate;
  result.status = std::system(run.c_str());
  result.results = json::parse(ReadText(dir / "out" / "results.json"), nullptr, false);
  result.report = ReadText(dir / "out" / "report.txt");
  result.stderr_text = ReadText(dir / "stderr.txt");
  if (resume) {
    const std::string again = run + " --resume";
    EXPECT_EQ(std::system(again.c_str()), 0) << again;
    result.resumed = json::parse(ReadText(dir / "out" / "results.json"), nullptr, false);
  }
  if (predict) {
    // The patrol vessel: 30 m at 6 m/s.
    const std::string command = binary + " predict " + (dir / "out").string() +
                                " --length 30 --speed 6 --members 40 > /dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    result.predictions =
        json::parse(ReadText(dir / "out" / "predict" / "predictions.json"), nullptr, false);
  }
  fs::remove_all(dir);
  return result;
}

CommandRun SimulateAndRun(const std::string& name, const std::string& noise,
                          bool held_out = false, bool predict = false) {
  return SimulateAndRunConfig(name, Config(noise, held_out), predict);
}

const json* EstimateNamed(const json& results, const std::string& name) {
  for (const json& e : results["stages"][0]["estimates"]) {
    if (e["name"] == name) return &e;
  }
  return nullptr;
}

TEST(FilterErrorRun, ProcessNoiseOnTheRuddersEquationWhitensTheInnovations) {
  const CommandRun run = SimulateAndRun(
      "process", "{method: filter_error, angles: deg, measurement: {psi: {type: white, sigma: 0.1}}, "
                 "process: {xi2: auto}, prediction_steps: 5, gain: auto}",
      true, true);
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  ASSERT_TRUE(run.results.is_object());
  const json* q = EstimateNamed(run.results, "q.process.xi2");
  ASSERT_NE(q, nullptr) << run.results["stages"][0]["estimates"].dump();
  EXPECT_EQ((*q)["kind"], "noise");
  EXPECT_GT((*q)["value"].get<double>(), 0.0);
  EXPECT_EQ((*q)["unit"], "(rad/s)^2/s") << q->dump();  // xi2's unit squared, per second
  const json* sigma = EstimateNamed(run.results, "sigma.white.psi");
  ASSERT_NE(sigma, nullptr);
  EXPECT_EQ((*sigma)["unit"], "rad");  // the heading's, shown in degrees where it was read so
  EXPECT_NEAR((*sigma)["value"].get<double>(), 0.1 * M_PI / 180.0, 0.03 * M_PI / 180.0);
  const std::vector<json> named =
      testing::JsonFindingsOf(run.results, "disturbance_model", "process noise on xi2");
  ASSERT_EQ(named.size(), 1u) << testing::JsonFindingsText(run.results);
  EXPECT_NE(named[0]["message"].get<std::string>().find("psi white in 1 of 1"), std::string::npos)
      << named[0]["message"];
  EXPECT_TRUE(testing::JsonFindingsOf(run.results, "coloured_residuals", "").empty())
      << testing::JsonFindingsText(run.results);
  // The rudder's 0.1 deg noise is the process noise here: no input_noise warning (whose
  // advice, input corrections, the filter-error method does not take).
  EXPECT_TRUE(testing::JsonFindingsOf(run.results, "input_noise", "").empty())
      << testing::JsonFindingsText(run.results);
  const json& a = run.results["stages"][0]["residual_analysis"][0];
  EXPECT_TRUE(a["white"].get<bool>()) << a.dump();
  // The ship's parameters near the truth (T1 2.09, K -0.172).
  EXPECT_NEAR((*EstimateNamed(run.results, "K"))["value"].get<double>(), -0.1724, 0.02);
  // results.json: the disturbance and the held-out run predicted through the filter, where
  // the k-step prediction lies between the one-step prediction and the free run.
  const json& d = run.results["stages"][0]["disturbance"];
  ASSERT_TRUE(d.is_object()) << run.results["stages"][0].dump();
  EXPECT_EQ(d["method"], "filter_error");
  EXPECT_NE(d["model"].get<std::string>().find("process noise on xi2"), std::string::npos);
  ASSERT_EQ(d["predictions"].size(), 1u) << d.dump();
  const json& p = d["predictions"][0];
  EXPECT_EQ(p["experiment"], "check");
  EXPECT_EQ(p["steps"], 5);
  EXPECT_NEAR(p["seconds_ahead"].get<double>(), 0.5, 1e-9);
  EXPECT_GE(p["one_step_fit_percent"].get<double>(), p["k_step_fit_percent"].get<double>());
  EXPECT_GE(p["k_step_fit_percent"].get<double>(), p["free_run_fit_percent"].get<double>());
  // `predict` flies the identified process noise: its spectral density as estimated, and a
  // third interval per figure from members in their own gusts.
  const json& predicted = run.predictions;
  ASSERT_TRUE(predicted.is_object());
  ASSERT_EQ(predicted["process_noise"].size(), 1u) << predicted.dump();
  EXPECT_EQ(predicted["process_noise"][0]["state"], "xi2");
  EXPECT_DOUBLE_EQ(predicted["process_noise"][0]["spectral_density"].get<double>(),
                   (*q)["value"].get<double>());
  for (const json& f : predicted["figures"]) {
    EXPECT_EQ(f["disturbance_members"], 40) << f.dump();
    ASSERT_TRUE(f["disturbance_interval"][0].is_number()) << f.dump();
    EXPECT_LE(f["disturbance_interval"][0].get<double>(), f["disturbance_interval"][1].get<double>());
  }
}

// A block bootstrap resamples output error's residuals onto its simulation; under the
// filter-error method it is refused with a finding naming experiment_bootstrap, and the run
// goes on with the Fisher information (it overran its buffers: each sample has two rows).
TEST(FilterErrorRun, BlockBootstrapIsRefusedUnderTheFilterNotOverrun) {
  const CommandRun run = SimulateAndRun(
      "block_bootstrap",
      "{method: filter_error, process: {xi2: auto}}\n"
      "    uncertainty: {method: block_bootstrap, runs: 10}");
  ASSERT_TRUE(run.results.is_object()) << run.stderr_text;
  const std::vector<json> refused = testing::JsonFindingsOf(run.results, "bootstrap", "");
  ASSERT_FALSE(refused.empty()) << testing::JsonFindingsText(run.results);
  EXPECT_NE(refused[0]["message"].get<std::string>().find("experiment_bootstrap"),
            std::string::npos)
      << refused[0]["message"];
  EXPECT_NE(EstimateNamed(run.results, "q.process.xi2"), nullptr);
  EXPECT_GT((*EstimateNamed(run.results, "K"))["std_error"].get<double>(), 0.0);
}

TEST(FilterErrorRun, AutoNamesEveryCandidateAndKeepsTheBest) {
  // The method alone (noise: auto), after a global start of output error's; then resumed.
  const CommandRun run = SimulateAndRunConfig(
      "auto", Config("auto\n    global: {points: 8}", false), false, /*resume=*/true);
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  // The stage restored from its checkpoint keeps its disturbance report, and so its verdict
  // (which, without it, read output error's coloured residuals: input noise, doubtful).
  ASSERT_TRUE(run.resumed.is_object());
  EXPECT_EQ(run.resumed["stages"][0]["disturbance"], run.results["stages"][0]["disturbance"]);
  EXPECT_EQ(run.resumed["verdict"], run.results["verdict"]);
  EXPECT_EQ(run.resumed["stages"][0]["findings"], run.results["stages"][0]["findings"]);
  const std::string notes = run.results["stages"][0]["notes"].dump();
  // The global start that found the estimate every candidate started from is reported.
  EXPECT_TRUE(run.results["stages"][0].contains("global_start")) << notes;
  // Each ship parameter's start as configured; the chosen disturbance's noise parameters have
  // none (their solve started from the candidates' own), not values read past the end of
  // output error's starts (which differed with the thread count).
  const std::map<std::string, double> configured = {
      {"T1", 2.5}, {"T2", 0.26}, {"T3", 0.22}, {"K", -0.2}};
  int noise = 0;
  for (const json& e : run.results["stages"][0]["estimates"]) {
    const auto found = configured.find(e["name"].get<std::string>());
    if (found != configured.end()) {
      EXPECT_EQ(e["start"], found->second) << e.dump();
    }
    if (e["kind"] == "noise") {
      ++noise;
      EXPECT_TRUE(e["start"].is_null()) << e.dump();
    }
  }
  EXPECT_GE(noise, 1);
  EXPECT_NE(notes.find("noise auto: BIC"), std::string::npos) << notes;
  EXPECT_NE(notes.find("output_error"), std::string::npos) << notes;
  EXPECT_NE(notes.find("process(xi2)"), std::string::npos) << notes;
  EXPECT_NE(notes.find("chosen"), std::string::npos) << notes;
  EXPECT_NE(notes.find("output error's estimates were"), std::string::npos) << notes;
  EXPECT_NE(EstimateNamed(run.results, "q.process.xi2"), nullptr) << notes;
  // The same choice in results.json: output error first, one chosen, the least BIC.
  const json& d = run.results["stages"][0]["disturbance"];
  ASSERT_TRUE(d.is_object());
  EXPECT_EQ(d["method"], "auto");
  ASSERT_GE(d["candidates"].size(), 3u);
  EXPECT_EQ(d["candidates"][0]["name"], "output_error");
  int chosen = 0;
  double least = 1e300, chosen_bic = 0.0;
  for (const json& c : d["candidates"]) {
    if (!c["solved"].get<bool>()) continue;
    least = std::min(least, c["bic"].get<double>());
    if (c["chosen"].get<bool>()) {
      ++chosen;
      chosen_bic = c["bic"].get<double>();
    }
  }
  EXPECT_EQ(chosen, 1) << d.dump();
  EXPECT_EQ(chosen_bic, least);
  // The combined candidate, started from the solutions of the two it nests, is at least as
  // likely as either.
  std::map<std::string, double> nll;
  for (const json& c : d["candidates"]) {
    if (c["solved"].get<bool>()) nll[c["name"]] = c["negative_log_likelihood"].get<double>();
  }
  int combined = 0;
  for (const auto& [name, value] : nll) {
    const size_t plus = name.find(" + ");
    if (plus == std::string::npos) continue;
    ++combined;
    for (const std::string& part : {name.substr(0, plus), name.substr(plus + 3)}) {
      ASSERT_TRUE(nll.count(part)) << part << "\n" << d.dump();
      EXPECT_LE(value, nll[part] + 1e-6 * std::abs(nll[part])) << name << " vs " << part;
    }
  }
  EXPECT_EQ(combined, 1) << d.dump();
}

// Noise-free records (the shipped cargo example: 0.02 s, the rudder read with cubic
// interpolation) leave output error's residuals coloured by the integrator's error alone: auto
// keeps output error and solves no candidate (there is no disturbance to identify).
TEST(FilterErrorRun, AutoKeepsOutputErrorOnNoiseFreeRecords) {
  const std::string config =
      ReadText(fs::path(VESSELID_SOURCE_DIR) / "configs" / "nomoto_cargo.yaml") +
      "    noise: auto\n";
  const CommandRun run = SimulateAndRunConfig("auto_noise_free", config);
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  const std::string notes = run.results["stages"][0]["notes"].dump();
  EXPECT_NE(notes.find("noise auto: output error kept"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("noise auto: BIC"), std::string::npos) << notes;
  EXPECT_EQ(run.results["stages"][0]["disturbance"]["candidates"].size(), 0u)
      << run.results["stages"][0]["disturbance"].dump();
  EXPECT_EQ(EstimateNamed(run.results, "q.process.xi2"), nullptr);
}

TEST(FilterErrorRun, UnknownOutputsStatesAndValuesAreRefusedWithTheKey) {
  for (const auto& [noise, says] : std::vector<std::pair<std::string, std::string>>{
           {"{measurement: {r2: white}}", "r2"},
           {"{process: {nope: auto}}", "process.nope: unknown key (allowed: psi, xi1, xi2)"},
           {"{measurement: {psi: {type: pink}}}", "unknown measurement noise 'pink'"},
           {"{wave: {psi: {zeta: 1.5}}}", "must be in (0, 1)"},
           {"{bias: {psi: {q: -1, initial_sd: 1}}}", "must be > 0"},
           {"{method: sometimes}", "unknown method 'sometimes'"},
           {"sometimes", "unknown method 'sometimes'"},
           {"[auto]", "expected output_error, filter_error, auto or a map"},
           {"{prediction_steps: 0}", "must be >= 1"},
           {"{gain: sometimes}", "expected auto or time_varying"},
           {"{measurement: {psi: {type: ar1, sigma: 0, tau: 1, white: true}}}", "must be > 0"},
           {"{wave: {psi: {omega: -1, sigma: 1}}}", "must be > 0"},
           // The parts are the filter's: silently unused under auto or output error before.
           {"{method: auto, measurement: {psi: {type: ar1}}}",
            "noise.measurement: not used under method auto, which chooses"},
           {"{method: output_error, process: {xi2: auto}}",
            "noise.process: not used under method output_error"}}) {
    const fs::path dir = fs::temp_directory_path() / "vesselid_filter_error_refused";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "config.yaml") << Config(noise);
    const std::string command = std::string(VESSELID_BINARY) + " run " +
                                (dir / "config.yaml").string() + " --out " +
                                (dir / "out").string() + " > " +
                                (dir / "out.txt").string() + " 2>&1";
    EXPECT_NE(std::system(command.c_str()), 0) << noise;
    const std::string text = ReadText(dir / "out.txt");
    EXPECT_NE(text.find(says), std::string::npos) << noise << "\n" << text;
    EXPECT_NE(text.find("config.yaml:"), std::string::npos) << text;
    EXPECT_NE(text.find("noise"), std::string::npos) << text;
    EXPECT_FALSE(fs::exists(dir / "out" / "results.json")) << noise;
    fs::remove_all(dir);
  }
}

namespace {

// Two candidates of one ship on the patrol vessel's two records: output error, and the same
// stage with process noise on the rudder's equation.
std::string SelectionConfig() {
  std::string config = Config("{method: output_error}", true);
  // Both records in the stage: select holds each out in turn.
  const std::string from = "    experiments: [multisine]\n    validation: [check]";
  config.replace(config.find(from), from.size(), "    experiments: [multisine, check]");
  const std::string stage = config.substr(config.find("stages:\n"));
  std::string gusts = stage;
  const std::string noise = "noise: {method: output_error}";
  gusts.replace(gusts.find(noise), noise.size(),
                "noise: {method: filter_error, process: {xi2: auto}, prediction_steps: 5}");
  // The candidate's stages indented under its name.
  std::string indented;
  for (size_t at = 0; at < gusts.size();) {
    const size_t end = gusts.find('\n', at);
    indented += "      " + gusts.substr(at, end - at) + "\n";
    at = end == std::string::npos ? gusts.size() : end + 1;
  }
  return config + "select:\n  experiments: [multisine, check]\n  candidates:\n"
                  "    - name: output_error\n    - name: gusts\n" + indented;
}

}  // namespace

// `select` scores candidates with and without a disturbance model the same way: the
// likelihood of the fit on every run (the filter's, or output error's Gaussian one with the
// residual variances estimated: BIC_L), and a filter-error candidate's held-out runs are also
// predicted through its filter. On a record whose output-error residuals are coloured by the
// rudder's noise, the process-noise candidate has the lower BIC_L.
TEST(FilterErrorRun, SelectScoresCandidatesWithAndWithoutADisturbanceTheSameWay) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_filter_error_select";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "config.yaml") << SelectionConfig();
  const std::string binary = VESSELID_BINARY;
  ASSERT_EQ(std::system((binary + " simulate " + (dir / "config.yaml").string() + " --out " +
                         dir.string() + " > /dev/null")
                            .c_str()),
            0);
  const std::string select = binary + " select " + (dir / "config.yaml").string() + " --data " +
                             dir.string() + " --out " + (dir / "out").string() +
                             " --quiet > /dev/null 2> " + (dir / "stderr.txt").string();
  const int status = std::system(select.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 1 && WEXITSTATUS(status) != 2)
      << ReadText(dir / "stderr.txt");
  const json results = json::parse(ReadText(dir / "out" / "results.json"), nullptr, false);
  ASSERT_TRUE(results.is_object()) << ReadText(dir / "stderr.txt");
  const json& s = results["selection"];
  ASSERT_EQ(s["candidates"].size(), 2u) << s.dump();
  const json& oe = s["candidates"][0];
  const json& gusts = s["candidates"][1];
  EXPECT_TRUE(s["likelihoods_comparable"].get<bool>());
  EXPECT_EQ(oe["disturbance"], "");
  EXPECT_NE(gusts["disturbance"].get<std::string>().find("process noise on xi2"),
            std::string::npos)
      << gusts.dump();
  // k: 4 ship parameters, and a heading variance or the disturbance's two.
  EXPECT_EQ(oe["likelihood_unknowns"], 5);
  EXPECT_EQ(gusts["likelihood_unknowns"], 6);
  EXPECT_EQ(oe["likelihood_samples"], gusts["likelihood_samples"]);
  EXPECT_LT(gusts["likelihood_bic"].get<double>(), oe["likelihood_bic"].get<double>()) << s.dump();
  // Through the filter: the gusts candidate's held-out runs, not output error's.
  EXPECT_TRUE(oe["k_step_fit_percent"].is_null());
  EXPECT_EQ(gusts["prediction_steps"], 5);
  EXPECT_GE(gusts["one_step_fit_percent"].get<double>(), gusts["k_step_fit_percent"].get<double>());
  EXPECT_GE(gusts["k_step_fit_percent"].get<double>(), gusts["score"].get<double>());
  const std::string report = ReadText(dir / "out" / "report.txt");
  EXPECT_NE(report.find("BIC_L"), std::string::npos);
  EXPECT_NE(report.find("k-step %"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace filter_error_run_test
}  // namespace vesselid
