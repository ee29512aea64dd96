// The HTML run report: base64 and min/max decimation on known cases, a hand-made result with
// awkward names (with and without gnuplot), and the shipped Erunsal hierarchy end to end: every
// plot results.json implies is in report.html and renders in headless Chromium.
#include "engine/config/config.h"
#include "engine/report/report_html.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <set>

#include "engine/report/base64.h"
#include "engine/report/decimation.h"
#include "engine/base/parallel_for.h"
#include "engine/report/report_figures.h"
#include "engine/report/started_gnuplots.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "tests/support/shipped_config.h"

namespace vesselid {
namespace report_html_test {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

size_t Count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The value of the first `name="..."` in an HTML text, or "(none)".
std::string Attribute(const std::string& html, const std::string& name) {
  const size_t at = html.find(name + "=\"");
  if (at == std::string::npos) return "(none)";
  const size_t begin = at + name.size() + 2;
  return html.substr(begin, html.find('"', begin) - begin);
}

constexpr char kNoGnuplot[] = "gnuplot not found (Debian gnuplot-nox; .ci/setup installs it)";

bool HaveProgram(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

TEST(Base64Test, KnownVectors) {
  // RFC 4648 section 10, and bytes that use the last two alphabet characters.
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64Encode(std::string("\xff\x00\xfe\xfb", 4)), "/wD++w==");
}

TEST(DecimationTest, KeepsExtremesWithinBudget) {
  std::mt19937 random(3);
  std::normal_distribution<double> step(0.0, 1.0);
  std::vector<double> y(100000);
  for (size_t k = 1; k < y.size(); ++k) y[k] = y[k - 1] + step(random);
  y[31337] = 1e4;  // single-sample spikes
  y[77777] = -1e4;
  const std::vector<size_t> kept = MinMaxDecimation(y, 2000);
  EXPECT_LE(kept.size(), 2000u);
  EXPECT_GE(kept.size(), 1900u);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  EXPECT_EQ(std::set<size_t>(kept.begin(), kept.end()).size(), kept.size());
  EXPECT_EQ(kept.front(), 0u);
  EXPECT_EQ(kept.back(), y.size() - 1);
  EXPECT_TRUE(std::count(kept.begin(), kept.end(), 31337u) == 1);
  EXPECT_TRUE(std::count(kept.begin(), kept.end(), 77777u) == 1);
  // Extremes of a stretch of buckets are kept too.
  double low = y[50001], high = y[50001];
  for (size_t k : kept) {
    if (k <= 50000) continue;
    low = std::min(low, y[k]);
    high = std::max(high, y[k]);
  }
  EXPECT_EQ(low, *std::min_element(y.begin() + 50001, y.end()));
  EXPECT_EQ(high, *std::max_element(y.begin() + 50001, y.end()));

  const std::vector<double> few = {3, 1, 2};
  EXPECT_EQ(MinMaxDecimation(few, 2000), (std::vector<size_t>{0, 1, 2}));
  EXPECT_LE(MinMaxDecimation(y, 3).size(), 3u);
}

TEST(RenderFiguresTest, FiguresAfterAFailingOneAreStillDrawn) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  Figure good;
  good.width = 300;
  good.height = 200;
  good.data = {"0 1\n1 2\n2 NaN\n3 0\n"};
  good.script = "plot D0 using 1:2 with lines title " + GnuplotString("it's a_b");
  Figure bad = good;
  bad.script = "plot D0 using 1:2 with no_such_style";
  std::vector<Figure> figures = {good, bad, good};
  figures[0].name = "first";
  figures[1].name = "broken";
  figures[2].name = "third";
  const FigureRendering rendering = RenderFigures(figures);
  ASSERT_EQ(rendering.svg.size(), 3u);
  EXPECT_NE(rendering.svg[0].find("</svg>"), std::string::npos);
  EXPECT_TRUE(rendering.svg[1].empty());
  EXPECT_NE(rendering.svg[2].find("</svg>"), std::string::npos);
  EXPECT_NE(rendering.error.find("figure broken"), std::string::npos) << rendering.error;
  EXPECT_NE(rendering.svg[0].find("it's a_b"), std::string::npos);
}

// A process killed while drawing leaves its "vesselid_report_<pid>_*" folder in the temporary
// directory: the next rendering removes it, and keeps one whose process is alive (this one's).
TEST(RenderFiguresTest, FoldersOfKilledProcessesAreRemoved) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // gone: its pid names a dead process
  const fs::path stale = fs::temp_directory_path() /
                         ("vesselid_report_" + std::to_string(child) + "_killed");
  const fs::path alive = fs::temp_directory_path() /
                         ("vesselid_report_" + std::to_string(::getpid()) + "_drawing");
  for (const fs::path& folder : {stale, alive}) {
    fs::create_directories(folder);
    std::ofstream(folder / "D0.dat") << "0 1\n";
  }
  Figure figure;
  figure.width = 300;
  figure.height = 200;
  figure.data = {"0 1\n1 2\n"};
  figure.script = "plot D0 using 1:2 with lines";
  EXPECT_TRUE(RenderFigures({figure}).error.empty());
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(alive / "D0.dat"));
  fs::remove_all(alive);
}

// gnuplots started ahead (as a run that writes report.html does) draw the same figures as
// ones started for the report, stop at a failing figure alike, and are each used once.
TEST(RenderFiguresTest, StartedGnuplotsDrawWhatOnesStartedLaterDraw) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  Figure good;
  good.width = 300;
  good.height = 200;
  good.data = {"0 1\n1 2\n2 NaN\n3 0\n"};
  good.script = "plot D0 using 1:2 with lines title 'a'";
  Figure bad = good;
  bad.script = "plot D0 using 1:2 with no_such_style";
  std::vector<Figure> figures = {good, good, bad, good};
  for (size_t i = 0; i < figures.size(); ++i) figures[i].name = "f" + std::to_string(i);
  figures[1].script = "plot D0 using 1:2 with points title 'b'";
  const FigureRendering later = RenderFigures(figures);
  StartGnuplots(4);  // more than the groups: the rest are left unused
  const FigureRendering started = RenderFigures(figures);
  EXPECT_EQ(started.svg, later.svg);
  EXPECT_TRUE(started.svg[2].empty());
  EXPECT_NE(started.svg[3].find("</svg>"), std::string::npos);
  EXPECT_NE(started.error.find("figure f2"), std::string::npos) << started.error;
  EXPECT_NE(started.error.find("no_such_style"), std::string::npos) << started.error;
  // Each group of figures (one per core) took one started gnuplot; the rest are left, each
  // runs one script (a script it cannot load is its error), then none is left and
  // RenderFigures starts its own.
  const int groups = std::min(static_cast<int>(figures.size()), ParallelThreads(0));
  int left = 0, status = 0;
  std::string messages;
  while (RunStartedGnuplot("/nonexistent/vesselid.gp", &status, &messages)) {
    ++left;
    EXPECT_NE(status, 0);
    EXPECT_NE(messages.find("vesselid.gp"), std::string::npos) << messages;
  }
  EXPECT_EQ(left, 4 - groups);
  EXPECT_EQ(RenderFigures(figures).svg, later.svg);
}

// A one-stage result of a first-order Nomoto model with names that need escaping.
class HandMadeReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_report_html_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "run.csv") << "t,delta,psi\n0,0,0\n1,0.1,0.01\n2,0.1,0.03\n";
    std::ofstream(dir_ / "run.yaml") << R"(description: "tug <trials> & co"
model: {family: nomoto, type: first_order}
experiments:
  - {name: "it's <b>_1", file: run.csv, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: "stage \"one\" & co"
    experiments: ["it's <b>_1"]
    parameters:
      T: {start: 3, lower: 0.1, upper: 50}
      K: {start: -0.1, lower: -1, upper: 1}
)";
    std::string error;
    ASSERT_TRUE(
        LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config_, &error))
        << error;
    StageResult stage;
    stage.name = "stage \"one\" & co";
    stage.model = config_.model->info().name;
    stage.summary.name = stage.name;
    stage.summary.usable = true;
    LocalSolveSummary solve;
    solve.run = solve.usable = true;
    solve.iterations = 3;
    solve.cost_history = {1.0, 0.1, 0.01, 0.009};
    solve.final_cost = 0.009;
    solve.termination = "CONVERGENCE";
    stage.summary.refinements = {solve};
    stage.summary.chosen = 0;
    ExperimentFit fit;
    fit.experiment = "it's <b>_1";
    fit.rms_cost = 0.01;
    fit.channels.push_back({fit.experiment, "psi", 3, 0.01, 0.008, 0.99, 90.0});
    const double nan = std::nan("");
    fit.trace.t = {0, 0.5, 1, 1.5, 2};
    fit.trace.names = {"psi_measured", "psi_simulated"};
    fit.trace.columns = {{0, nan, 0.01, nan, 0.03}, {0, 0.004, 0.011, 0.02, 0.028}};
    stage.summary.fits = {fit};
    const EstimateKind kParameter = EstimateKind::kParameter;
    const ParameterRole kFree = ParameterRole::kFree;
    Estimate t{"T", kParameter, kFree, "", 2.0, 3.0, 0.1, 0.1, 50.0, false};
    Estimate k{"K", kParameter, kFree, "", -0.17, -0.1, nan, -1.0, 1.0, true};
    stage.estimates = {t, k};
    stage.correlation_names = {"T", "K"};
    stage.correlation = Eigen::Matrix2d::Identity();
    stage.correlation(0, 1) = stage.correlation(1, 0) = -0.9;
    result_.stages = {stage};
    result_.parameters = {{"T", 2.0, 0.1, kFree, {stage.name}, "stage", false},
                          {"K", -0.17, nan, kFree, {stage.name}, "stage", true}};
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  RunConfig config_;
  RunResult result_;
};

TEST_F(HandMadeReportTest, EscapesNamesAndDrawsEveryPlot) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  const std::string html = RunReportHtml(config_, result_);
  EXPECT_EQ(Count(html, "<img class=\"plot\""), 3u);  // trace, correlation, cost history
  EXPECT_EQ(Count(html, "src=\"data:image/svg+xml;base64,"), 3u);
  EXPECT_EQ(html.find("<b>_1"), std::string::npos);
  EXPECT_NE(html.find("it&#39;s &lt;b&gt;_1"), std::string::npos);
  EXPECT_NE(html.find("stage &quot;one&quot; &amp; co"), std::string::npos);
  // The config's `description` heads the run's table.
  EXPECT_NE(html.find("<td>tug &lt;trials&gt; &amp; co</td>"), std::string::npos);
  EXPECT_NE(html.find("undetermined"), std::string::npos);
  EXPECT_EQ(html.find("class=\"notice\""), std::string::npos);
}

// A stage of 20 records draws the 12 that fit worst, says so, and keeps every record's table.
TEST_F(HandMadeReportTest, ManyRecordsDrawTheWorstTwelve) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  const ExperimentFit fit = result_.stages[0].summary.fits[0];
  std::vector<ExperimentFit>& fits = result_.stages[0].summary.fits;
  fits.clear();
  for (int i = 0; i < 20; ++i) {
    ExperimentFit f = fit;
    f.experiment = "run" + std::to_string(i);
    f.rms_cost = 0.01 * (1 + (i * 7) % 20);  // every cost once, in shuffled order
    for (ChannelMetrics& c : f.channels) c.experiment = f.experiment;
    fits.push_back(f);
  }
  const std::string html = RunReportHtml(config_, result_);
  EXPECT_EQ(Count(html, "<img class=\"plot\""), 14u);  // 12 traces, correlation, cost history
  EXPECT_NE(html.find("20 records: figures for the 12 that fit worst"), std::string::npos);
  for (int i = 0; i < 20; ++i) {
    const std::string name = "run" + std::to_string(i);
    const bool worst = 1 + (i * 7) % 20 > 8;  // costs 0.09 to 0.20
    EXPECT_EQ(html.find(name + ": measured and simulated outputs") != std::string::npos, worst)
        << name;
    EXPECT_NE(html.find("<h4>" + name + "</h4>"), std::string::npos) << name;
  }
}

TEST_F(HandMadeReportTest, WithoutGnuplotKeepsTablesAndSaysWhy) {
  const char* path = std::getenv("PATH");
  const std::string saved = path ? path : "";
  setenv("PATH", (dir_ / "no_programs_here").c_str(), 1);
  std::string error;
  const bool written = WriteRunReport(config_, result_, dir_.string(), &error);
  setenv("PATH", saved.c_str(), 1);
  ASSERT_TRUE(written) << error;
  const std::string html = ReadText(dir_ / "report.html");
  EXPECT_EQ(Count(html, "<img"), 0u);
  EXPECT_NE(html.find("class=\"notice\""), std::string::npos);
  EXPECT_NE(html.find("gnuplot-nox"), std::string::npos);
  EXPECT_NE(html.find("Paper-style tables"), std::string::npos);
  EXPECT_NE(html.find("[1.804, 2.196]"), std::string::npos);  // T +- 1.96 SE
}

// Figures of a fit list in results.json: a trace per simulated record (MAE known), and an x-y
// track per record with both horizontal positions (the Erunsal model's x, y) measured.
size_t Records(const nlohmann::json& fit) {
  std::set<std::string> records, with_x, with_y;
  for (const nlohmann::json& m : fit.at("metrics")) {
    if (!m.at("mae").is_number() || m.at("samples").get<int>() == 0) continue;
    const std::string name = m.at("experiment").get<std::string>();
    const std::string record = name.substr(0, name.find_first_of("@#"));
    records.insert(record);
    if (m.at("output") == "x") with_x.insert(record);
    if (m.at("output") == "y") with_y.insert(record);
  }
  size_t tracks = 0;
  for (const std::string& record : with_x) tracks += with_y.count(record);
  return records.size() + tracks;
}

// The plots report.html has for a results.json (report_html.h): per stage a trace figure per
// record of its fit and of its validation (and its x-y track), a correlation heat map over two or
// more shared parameters, a cost history when a refinement iterated or a global start evaluated
// twice, lasso paths and samples for step regression, the residual analysis of the four worst
// channels; a trace figure per final validation record.
size_t ExpectedPlots(const nlohmann::json& results) {
  size_t plots = 0;
  for (const nlohmann::json& stage : results.at("stages")) {
    plots += Records(stage.at("fit"));
    if (stage.contains("validation")) plots += Records(stage.at("validation"));
    if (stage.contains("correlation")) {
      size_t shared = 0;
      for (const nlohmann::json& name : stage.at("correlation").at("names")) {
        shared += name.get<std::string>().find('[') == std::string::npos ? 1 : 0;
      }
      plots += shared >= 2 ? 1 : 0;
    }
    bool iterated = stage.contains("global_start") &&
                    stage.at("global_start").at("evaluations").get<int>() >= 2;
    for (const nlohmann::json& r : stage.at("refinements")) {
      iterated = iterated || r.at("iterations").get<int>() >= 1;
    }
    plots += iterated ? 1 : 0;
    if (stage.contains("residual_analysis")) {  // MATLAB resid's figure of the 4 worst channels
      size_t tested = 0;
      for (const nlohmann::json& a : stage.at("residual_analysis")) tested += a.at("tested").get<bool>();
      plots += std::min<size_t>(tested, 4);
    }
    if (stage.contains("step_regression")) {
      const nlohmann::json& s = stage.at("step_regression");
      plots += s.at("terms").empty() ? 0 : 1;
      plots += s.at("damping_samples").get<int>() + s.at("inertia_samples")[0].get<int>() +
                           s.at("inertia_samples")[1].get<int>() >
                       0
                   ? 1
                   : 0;
    }
  }
  if (results.contains("final_validation")) plots += Records(results.at("final_validation"));
  return plots;
}

TEST(ReportHtmlTest, ErunsalHierarchyReportRendersEveryPlot) {
  ASSERT_TRUE(HaveProgram("gnuplot")) << kNoGnuplot;
  const fs::path out = fs::temp_directory_path() / "vesselid_report_html_erunsal";
  testing::SimulateAndRunInto("erunsal_hierarchy", out);
  ASSERT_FALSE(HasFatalFailure());

  std::ifstream in(out / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  const size_t expected = ExpectedPlots(results);
  EXPECT_GT(expected, 0u);
  const std::string html = ReadText(out / "report.html");
  ASSERT_FALSE(html.empty());
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(Count(html, "src=\""), Count(html, "src=\"data:image/svg+xml;base64,"));
  EXPECT_EQ(Count(html, "<img class=\"plot\""), expected);
  EXPECT_EQ(Count(html, "src=\"data:image/svg+xml;base64,"), expected);
  EXPECT_EQ(html.find("class=\"notice\""), std::string::npos);

  ASSERT_TRUE(HaveProgram("chromium")) << "chromium not found (.ci/setup installs it)";
  const fs::path profile = out / "chromium_profile";
  const fs::path dom = out / "dom.html";
  const std::string chromium =
      "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync "
      "--user-data-dir=" +
      profile.string() + " --virtual-time-budget=10000 --dump-dom file://" +
      fs::absolute(out / "report.html").string() + " > " + dom.string() + " 2> /dev/null";
  ASSERT_EQ(std::system(chromium.c_str()), 0) << chromium;
  const std::string dumped = ReadText(dom);
  EXPECT_EQ(Attribute(dumped, "data-plots-loaded"), std::to_string(expected));
  EXPECT_EQ(Attribute(dumped, "data-plots-total"), std::to_string(expected));
  fs::remove_all(out);
}

}  // namespace report_html_test
}  // namespace vesselid
