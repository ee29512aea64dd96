// From a stage's fits to its residual analysis and on to its warnings and report lines:
// residuals taken at each channel's own samples (a heading compared modulo one turn where the
// experiment wraps it), inputs read from the experiment's input cache at the sample nodes,
// the coloured-residual warning (not for noise-free data or failed fits), and report.txt's
// summary of many segments.
#include "engine/output/residual_report.h"
#include "engine/report/residual_html.h"

#include <cmath>
#include <random>

#include "engine/base/angle.h"
#include "engine/run/fit_residuals.h"
#include "engine/diagnose/residual_findings.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace residual_report_test {

ModelInfo HeadingModel() {
  ModelInfo info;
  info.name = "test";
  info.inputs = {"delta"};
  info.outputs = {"psi", "r"};
  return info;
}

// An experiment of `nodes` nodes 0.1 s apart, two RK4 steps per interval, whose input cache
// holds `u[k]` at node k and unrelated values at the other rows.
Experiment MakeExperiment(const std::vector<double>& u, bool wrap_psi) {
  Experiment e;
  e.name = "run1";
  e.num_inputs = 1;
  const int nodes = static_cast<int>(u.size());
  for (int k = 0; k < nodes; ++k) e.node_time.push_back(0.1 * k);
  e.node_substeps.assign(nodes - 1, 2);
  e.node_step.assign(nodes - 1, 0.05);
  e.input_cache.assign(3 * 2 * (nodes - 1) + 1, 1e3);  // rows between nodes: far off
  for (int k = 0; k < nodes; ++k) e.input_cache[6 * k] = u[k];
  e.wrapped_outputs = {wrap_psi, false};
  return e;
}

TEST(FitResiduals, WrappedHeadingAndInputsAtTheSampleNodes) {
  std::mt19937 engine(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  const int nodes = 3000;
  std::vector<double> u(nodes);
  for (double& v : u) v = noise(engine);
  ExperimentFit fit;
  fit.experiment = "run1";
  fit.trace.t.resize(nodes);
  fit.trace.names = {"psi_measured", "psi_simulated", "r_measured", "r_simulated"};
  fit.trace.columns.assign(4, std::vector<double>(nodes, NAN));
  for (int k = 0; k < nodes; ++k) {
    fit.trace.t[k] = 0.1 * k;
    // The heading hovers at the wrap (+-pi); the residual follows the input two samples back.
    const double truth = M_PI + 0.05 * std::sin(0.2 * k);
    const double e = (k >= 2 ? 0.02 * u[k - 2] : 0.0) + 0.01 * noise(engine);
    fit.trace.columns[0][k] = WrapAngle(truth);
    fit.trace.columns[1][k] = WrapAngle(truth + e);
    if (k % 2 == 0) {  // yaw rate sampled at every other node, white residual
      fit.trace.columns[2][k] = 0.0;
      fit.trace.columns[3][k] = 0.01 * noise(engine);
    }
  }
  fit.channels.push_back({"run1", "psi", nodes, 0.02, 0.02, 0.9, 50.0, 0.1, 0.01});
  fit.channels.push_back({"run1", "r", nodes / 2, 0.01, 0.01, 0.9, 50.0, 0.1, 0.01});
  ExperimentFit diverged;
  diverged.experiment = "run2";
  diverged.diverged = true;

  const ModelInfo info = HeadingModel();
  std::vector<ResidualAnalysis> wrapped =
      AnalyseFitResiduals(info, {MakeExperiment(u, true)}, {fit, diverged});
  ASSERT_EQ(wrapped.size(), 2u);  // the diverged run is left out
  const ResidualAnalysis& psi = wrapped[0];
  EXPECT_EQ(psi.output, "psi");
  EXPECT_EQ(psi.samples, nodes);
  ASSERT_EQ(psi.cross_correlation.size(), 1u);
  EXPECT_EQ(psi.cross_correlation[0].input, "delta");
  EXPECT_TRUE(psi.input_correlated);
  EXPECT_NEAR(psi.cross_correlation[0].values[25 + 2], 0.02 / std::sqrt(0.0005), 0.05);
  EXPECT_TRUE(psi.white);  // the input's white part: white residuals
  EXPECT_FALSE(psi.noise_free);
  const ResidualAnalysis& r = wrapped[1];
  EXPECT_EQ(r.output, "r");
  EXPECT_EQ(r.samples, nodes / 2);
  EXPECT_TRUE(r.white);
  EXPECT_FALSE(r.input_correlated);
  EXPECT_FALSE(r.irregular());

  // Compared unwrapped, the same heading's residuals jump by whole turns where the two sit
  // on either side of +-pi: a periodic pattern, coloured.
  const std::vector<ResidualAnalysis> unwrapped =
      AnalyseFitResiduals(info, {MakeExperiment(u, false)}, {fit});
  EXPECT_FALSE(unwrapped[0].white);
}

TEST(FitResiduals, NoiseFreeDataAreMarked) {
  std::vector<double> u(200, 0.0);
  for (int k = 0; k < 200; ++k) u[k] = std::sin(0.1 * k);
  ExperimentFit fit;
  fit.experiment = "run1";
  fit.trace.t.resize(200);
  fit.trace.names = {"psi_measured", "psi_simulated"};
  fit.trace.columns.assign(2, std::vector<double>(200));
  for (int k = 0; k < 200; ++k) {
    fit.trace.t[k] = 0.1 * k;
    fit.trace.columns[0][k] = std::cos(0.1 * k);
    fit.trace.columns[1][k] = std::cos(0.1 * k) + 1e-9 * std::sin(0.01 * k);  // integration error
  }
  fit.channels.push_back({"run1", "psi", 200, 1e-9, 1e-9, 1.0 - 1e-17, 100.0, 0.5, 1e-3});
  const std::vector<ResidualAnalysis> a =
      AnalyseFitResiduals(HeadingModel(), {MakeExperiment(u, false)}, {fit});
  ASSERT_EQ(a.size(), 1u);
  EXPECT_FALSE(a[0].white);
  EXPECT_TRUE(a[0].noise_free);
  StageResult stage;
  stage.name = "s";
  stage.residuals = a;
  std::vector<Finding> findings;
  AddResidualFindings(stage, &findings);
  EXPECT_TRUE(findings.empty());
  EXPECT_NE(DescribeResiduals(a[0]).find("noise-free data"), std::string::npos);
}

ResidualAnalysis Channel(const std::string& experiment, bool white, double lag1) {
  ResidualAnalysis a;
  a.experiment = experiment;
  a.output = "psi";
  a.samples = 500;
  a.lags = 25;
  a.autocorrelation.assign(26, 0.0);
  a.autocorrelation[0] = 1.0;
  a.autocorrelation[1] = a.lag1 = lag1;
  a.ljung_box_q = white ? 20.0 : 900.0;
  a.ljung_box_p = white ? 0.75 : 1e-30;
  a.white = white;
  a.band_99 = 2.58 / std::sqrt(500.0);
  a.band_95 = 1.96 / std::sqrt(500.0);
  return a;
}

TEST(ResidualFindings, ColouredChannelsNamedWorstFirstExceptFailedFits) {
  StageResult stage;
  stage.name = "multisine";
  stage.residuals = {Channel("run1", false, 0.4), Channel("run2", true, 0.01),
                     Channel("run3", false, 0.93), Channel("run4", false, 0.99)};
  ExperimentFit failed;
  failed.experiment = "run4";
  failed.channels.push_back({"run4", "psi", 500, 1.0, 1.0, -0.5, 0.0, 0.1, 0.01});  // R2 < 0
  stage.summary.fits = {failed};
  std::vector<Finding> findings;
  AddResidualFindings(stage, &findings);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].kind, FindingKind::kColouredResiduals);
  EXPECT_EQ(findings[0].stage, "multisine");
  EXPECT_EQ(findings[0].output, "psi");
  EXPECT_EQ(findings[0].count, 2);
  EXPECT_EQ(findings[0].message,
            "the residuals of psi are coloured in 2 of 3 experiment(s) "
            "(Ljung-Box p < 0.01): run3 (lag-1 0.93), run1 (lag-1 0.40); the Hessian standard "
            "errors assume white residuals and are too narrow");
  // With the HAC reported the warning says so, with the ratios behind the choice.
  stage.summary.uncertainty.method = "sandwich_hac";
  stage.summary.uncertainty.method_reason = "auto: K 3.2x";
  findings.clear();
  AddResidualFindings(stage, &findings);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_NE(findings[0].message.find("; the standard errors reported are the sandwich_hac ones, "
                                     "which allow for serially correlated residuals (auto: K "
                                     "3.2x)"),
            std::string::npos)
      << findings[0].message;
}

TEST(ResidualReportText, OneLinePerChannelOrASummaryOfManySegments) {
  std::vector<ResidualAnalysis> few = {Channel("run1", false, 0.93), Channel("run2", true, 0.01)};
  EXPECT_EQ(ResidualAnalysesText(few, "  "),
            "  residuals run1 psi: coloured (lag-1 0.93, Ljung-Box p < 1e-16)\n"
            "  residuals run2 psi: white (lag-1 0.01, p 0.75)\n");
  std::vector<ResidualAnalysis> many;
  for (int k = 0; k < 12; ++k) {
    many.push_back(Channel("log@" + std::to_string(k), k != 3 && k != 7, k == 7 ? 0.8 : 0.5));
  }
  EXPECT_EQ(ResidualAnalysesText(many, "  "),
            "  residuals psi: 10 of 12 experiments white\n"
            "    log@7: coloured (lag-1 0.80, Ljung-Box p < 1e-16)\n"
            "    log@3: coloured (lag-1 0.50, Ljung-Box p < 1e-16)\n");
  const std::vector<const ResidualAnalysis*> plotted = ResidualsToPlot(many, 4);
  ASSERT_EQ(plotted.size(), 4u);
  EXPECT_EQ(plotted[0]->experiment, "log@7");
  EXPECT_EQ(plotted[1]->experiment, "log@3");
  Figure figure;
  EXPECT_TRUE(ResidualFigure("f", *plotted[0], &figure));
  EXPECT_EQ(figure.data.size(), 1u);  // no inputs: the autocorrelation panel alone
  EXPECT_NE(figure.script.find("99 % band"), std::string::npos);
  const std::string html = ResidualTableHtml(many);
  EXPECT_NE(html.find("10 of 12 channel(s) white"), std::string::npos);
  EXPECT_NE(html.find("<tr class=\"flagged\"><td>log@7</td>"), std::string::npos);
}

}  // namespace residual_report_test
}  // namespace vesselid
