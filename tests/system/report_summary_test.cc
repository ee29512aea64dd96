// The report read top-down (results_text.h, report_summary.h, run_fit_table.h,
// parameter_summary.h) on a hand-made result: a 20-run final validation gets one row per run
// in report.txt and report.html, worst first, with mean / median / worst rows named; a
// record's segments fold into one row and are drawn on their own time axis; a parameter on
// its bound is flagged and its interval clipped; a fused value outside every stage's estimate
// is explained; fixed parameters and initial states are counted apart.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "engine/config/config.h"
#include "engine/report/report_html.h"
#include "engine/report/report_plots.h"
#include "engine/output/results_json.h"
#include "engine/output/results_text.h"
#include "engine/output/run_fit_table.h"
#include "gtest/gtest.h"
#include "problems/registry.h"

namespace vesselid {
namespace report_summary_test {

namespace fs = std::filesystem;

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A fit of `experiment` with psi fit % `fit` over 100 samples, a trace from t0 for 10 s.
ExperimentFit Fit(const std::string& experiment, double fit, double t0 = 0.0) {
  ExperimentFit f;
  f.experiment = experiment;
  const double rmse = 0.01 * (100.0 - fit) / 10.0, spread = rmse / (1.0 - fit / 100.0);
  ChannelMetrics m{
      experiment, "psi", 100, rmse, 0.8 * rmse, 1.0 - (rmse * rmse) / (spread * spread), fit};
  f.channels = {m};
  f.rms_cost = rmse;
  for (int k = 0; k <= 10; ++k) f.trace.t.push_back(t0 + k);
  f.trace.names = {"psi_measured", "psi_simulated"};
  f.trace.columns.assign(2, std::vector<double>(11, 0.0));
  for (int k = 0; k <= 10; ++k) {
    f.trace.columns[0][k] = 0.01 * k;
    f.trace.columns[1][k] = 0.01 * k + rmse;
  }
  return f;
}

class ReportSummaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test process: ctest runs this suite's tests as parallel processes.
    dir_ = fs::temp_directory_path() / ("vesselid_report_summary_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "run.csv") << "t,delta,psi\n0,0,0\n1,0.1,0.01\n2,0.1,0.03\n";
    std::ofstream(dir_ / "run.yaml") << R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: train, file: run.csv, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: first
    parameters:
      T: {start: 3, lower: 0.1, upper: 50}
      K: {start: -0.1, lower: -1, upper: -0.001}
)";
    std::string error;
    ASSERT_TRUE(
        LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config_, &error))
        << error;
    const EstimateKind kParameter = EstimateKind::kParameter;
    const ParameterRole kShared = ParameterRole::kShared;
    const double nan = std::nan("");
    auto stage = [&](const std::string& name, double t, double k) {
      StageResult s;
      s.name = name;
      s.model = config_.model->info().name;
      s.summary.name = name;
      LocalSolveSummary solve;
      solve.run = solve.usable = true;
      solve.iterations = 3;
      solve.cost_history = {1.0, 0.1, 0.01};
      solve.final_cost = 0.01;
      solve.termination = "CONVERGENCE";
      s.summary.refinements = {solve};
      s.summary.chosen = 0;
      s.summary.fits = {Fit("train@1", 95.0), Fit("train@2", 93.0, 14000.0)};
      s.estimates = {
          {"T", kParameter, kShared, "", t, 3.0, 0.2, 0.1, 50.0, false},
          {"K", kParameter, kShared, "", k, -0.1, 0.002, -1.0, -0.001, false},
          {"delta_0", kParameter, ParameterRole::kFixed, "", 0.0, 0.0, nan, 0.0, 0.0, false},
          {"psi", EstimateKind::kInitialState, ParameterRole::kPerExperiment, "train@1", 0.01, 0.0,
           0.001, -1.0, 1.0, false},
          {"psi", EstimateKind::kInitialState, ParameterRole::kPerExperiment, "train@2", 0.02, 0.0,
           0.001, -1.0, 1.0, false}};
      return s;
    };
    result_.stages = {stage("first", 2.0, -0.001), stage("second", 2.2, -0.0012)};
    // T fused by information outside both stages' estimates (2.0, 2.2); K on its upper bound
    // with an interval reaching past it; delta_0 fixed.
    result_.parameters = {{"T", 2.5, 0.1, kShared, {"first", "second"}, "information", false},
                          {"K", -0.001, 0.0004, kShared, {"first", "second"}, "information", false},
                          {"delta_0", 0.0, nan, ParameterRole::kFixed, {}, "fixed", false}};
    config_.has_final_validation = true;
    for (int i = 1; i <= 20; ++i) {
      // Run 7 is the worst (-30.4 %), the others 42.5 .. 90 %.
      const double fit = i == 7 ? -30.4 : 40.0 + 2.5 * i;
      result_.final_validation.push_back(Fit("held" + std::to_string(i), fit));
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  RunConfig config_;
  RunResult result_;
};

TEST_F(ReportSummaryTest, TextReportHasEveryRunAndNamedSummaryRows) {
  const std::string text = RunResultToText(config_, result_);
  // Summary first: the final parameters before the first stage's details.
  const size_t summary = text.find("\nsummary\n"), stages = text.find("\nstages\n");
  ASSERT_NE(summary, std::string::npos) << text;
  ASSERT_NE(stages, std::string::npos) << text;
  EXPECT_LT(summary, stages);
  const std::string head = text.substr(0, stages);
  for (int i = 1; i <= 20; ++i) {
    EXPECT_EQ(Count(head, "  held" + std::to_string(i) + " "), 1u) << i << "\n" << head;
  }
  EXPECT_NE(head.find("mean of 20 runs"), std::string::npos) << head;
  EXPECT_NE(head.find("median of 20 runs"), std::string::npos) << head;
  EXPECT_NE(head.find("worst of 20 runs"), std::string::npos) << head;
  EXPECT_NE(head.find("worst psi: held7"), std::string::npos) << head;
  // Worst first: held7 (-30.4 %) before held1 (42.5 %) before held20 (90 %).
  EXPECT_LT(head.find("  held7 "), head.find("  held1 "));
  EXPECT_LT(head.find("  held1 "), head.find("  held20 "));
  EXPECT_NE(head.find("-30.40"), std::string::npos);
  // The training fit: one row for the record, its two segments folded in.
  EXPECT_TRUE(std::regex_search(head, std::regex("  train +2 "))) << head;
  // Bound, clipped interval, fusion note, counts.
  EXPECT_NE(head.find("on its upper bound -0.001"), std::string::npos) << head;
  EXPECT_NE(head.find("interval clipped to the bounds"), std::string::npos) << head;
  EXPECT_NE(head.find("[-0.001784, -0.001]"), std::string::npos) << head;
  EXPECT_NE(head.find("T = 2.5 lies outside every stage's estimate (2 in first, 2.2 in second)"),
            std::string::npos)
      << head;
  EXPECT_NE(head.find("2 parameters estimated, 1 held fixed; 4 initial states estimated"),
            std::string::npos)
      << head;
  // Per stage, initial states apart from parameters.
  EXPECT_NE(text.find("2 parameters estimated, 1 held fixed; 2 initial states estimated"),
            std::string::npos);
}

TEST_F(ReportSummaryTest, HtmlSummaryIsSortableAndNamed) {
  const std::string html = RunReportHtml(config_, result_);
  const size_t summary = html.find("<section id=\"summary\">");
  const size_t first_stage = html.find("<section id=\"stage-1\">");
  ASSERT_NE(summary, std::string::npos);
  ASSERT_LT(summary, first_stage);
  const std::string head = html.substr(summary, first_stage - summary);
  EXPECT_EQ(Count(head, "<table class=\"sortable runs\">"), 2u);  // training, validation
  for (int i = 1; i <= 20; ++i) {
    EXPECT_EQ(Count(head, "<td>held" + std::to_string(i) + "</td>"), 1u) << i;
  }
  EXPECT_NE(head.find("<th>mean of 20 runs</th>"), std::string::npos);
  EXPECT_NE(head.find("<th>median of 20 runs</th>"), std::string::npos);
  EXPECT_NE(head.find("<th>worst of 20 runs</th>"), std::string::npos);
  EXPECT_NE(head.find("-30.40 (held7)"), std::string::npos);
  EXPECT_LT(head.find("<td>held7</td>"), head.find("<td>held1</td>"));
  EXPECT_NE(head.find("on its upper bound -0.001 1/s; interval clipped to the bounds"),
            std::string::npos);
  EXPECT_NE(head.find("lies outside every stage&#39;s estimate"), std::string::npos);
  EXPECT_NE(html.find("table.sortable"), std::string::npos);  // the sorting script
  // A stage's estimate on its bound is flagged in the stage's table too.
  EXPECT_NE(html.find("<tr class=\"flagged\"><td>K</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>on its upper bound; interval clipped</td>"), std::string::npos);
}

TEST_F(ReportSummaryTest, JsonHasRunsCountsAndFlags) {
  const nlohmann::json j = RunResultToJson(config_, result_);
  const nlohmann::json& runs = j.at("final_validation").at("runs");
  EXPECT_EQ(runs.at("rows").size(), 20u);
  EXPECT_EQ(runs.at("rows")[0].at("run"), "held7");
  EXPECT_EQ(runs.at("summary").at("worst").at("psi").at("run"), "held7");
  EXPECT_TRUE(runs.at("worst_first").get<bool>());
  EXPECT_EQ(j.at("counts").at("fixed_parameters"), 1);
  EXPECT_EQ(j.at("counts").at("initial_states"), 4);
  EXPECT_EQ(j.at("parameters")[1].at("at_bound"), "upper");
  EXPECT_TRUE(j.at("parameters")[1].at("interval_clipped").get<bool>());
  EXPECT_TRUE(j.at("parameters")[0].contains("fusion_note"));
}

TEST_F(ReportSummaryTest, SegmentsArePlottedOnTheirOwnTimeAxis) {
  const std::vector<const ExperimentFit*> segments = {&result_.stages[0].summary.fits[0],
                                                      &result_.stages[0].summary.fits[1]};
  Figure figure;
  ASSERT_TRUE(TraceFigure("f", segments, {"psi"}, {{"psi", {"deg", 180.0 / M_PI}}}, &figure));
  // Two 10 s segments 14 000 s apart: drawn end to end over about 20 s.
  std::smatch range;
  ASSERT_TRUE(std::regex_search(figure.script, range,
                                std::regex(R"(set xrange \[([-0-9.e+]+):([-0-9.e+]+)\])")))
      << figure.script;
  EXPECT_LT(std::stod(range[2]) - std::stod(range[1]), 25.0) << figure.script;
  EXPECT_NE(figure.script.find("2 segments end to end"), std::string::npos);
  EXPECT_NE(figure.script.find("'psi [deg]'"), std::string::npos);
  EXPECT_NE(figure.script.find("'residual [deg]'"), std::string::npos);
  // The plotted values in degrees: the last measured sample 0.1 rad = 5.73 deg.
  EXPECT_NE(figure.data[0].find(" 5.729578"), std::string::npos) << figure.data[0];
}

}  // namespace report_summary_test
}  // namespace vesselid
