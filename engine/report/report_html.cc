#include "engine/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "engine/base/atomic_file.h"
#include "engine/base/elapsed.h"
#include "engine/output/finding_report.h"
#include "engine/output/held_out_start_text.h"
#include "engine/output/parameter_summary.h"
#include "engine/report/base64.h"
#include "engine/report/bootstrap_html.h"
#include "engine/report/finding_html.h"
#include "engine/report/held_out_parameters_html.h"
#include "engine/report/noise_model_html.h"
#include "engine/report/report_figures.h"
#include "engine/report/report_plots.h"
#include "engine/report/report_summary.h"
#include "engine/report/report_tables.h"
#include "engine/report/residual_html.h"
#include "engine/report/selection_html.h"
#include "engine/report/turning_html.h"
#include "engine/report/zigzag_html.h"
#include "engine/run/display_units.h"
#include "engine/run/held_out.h"

namespace vesselid {
namespace {

// How the held-out runs were started and scored, and with refitted starts each run's figures
// from its measured start (held_out_start_text.h).
std::string HeldOutStartHtml(const std::vector<ExperimentFit>& fits) {
  const std::string sentence = HeldOutStartSentence(fits);
  if (sentence.empty()) return "";
  std::string html = "<p>" + HtmlEscape(sentence) + "</p>\n";
  const std::string table = HeldOutStartTable(fits, "");
  if (!table.empty()) html += "<pre>" + HtmlEscape(table) + "</pre>\n";
  return html;
}

constexpr char kStyle[] = R"(<style>
body { font-family: "DejaVu Sans", Verdana, Arial, sans-serif; font-size: 14px; line-height: 1.45;
       color: #222; max-width: 1180px; margin: 0 auto; padding: 0 24px 60px; }
.warnings li, p.warning, .findings.failure li, p.verdict.failed { color: #8a1c1c; }
.findings.warning li, p.verdict.doubtful { color: #8a5a00; }
p.verdict.good { color: #1c6a1c; }
h1 { font-size: 24px; border-bottom: 2px solid #34506b; padding-bottom: 6px; }
h2 { font-size: 20px; margin-top: 44px; border-bottom: 1px solid #c8d0d8; padding-bottom: 3px; }
h3 { font-size: 16px; margin: 26px 0 6px; color: #34506b; }
h4 { font-size: 14px; margin: 18px 0 4px; }
table { border-collapse: collapse; margin: 6px 0 14px; font-size: 13px; }
th, td { border: 1px solid #d3d8de; padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: #edf1f5; font-weight: 600; }
td.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
tr:nth-child(even) td { background: #fafbfc; }
tr.fixed td { color: #777; }
tr.flagged td { color: #8a1c1c; }
table.sortable thead th { cursor: pointer; }
table.sortable tfoot th, table.sortable tfoot td { background: #edf1f5; }
.scroll { overflow-x: auto; max-width: 100%; }
table.paper { font-size: 12.5px; }
img.plot { display: block; max-width: 100%; height: auto; margin: 8px 0; }
.brief { font-family: "DejaVu Sans Mono", monospace; font-size: 12.5px; background: #f3f5f7;
         padding: 6px 10px; border-left: 3px solid #34506b; }
.notice { border: 1px solid #d9a400; background: #fff6d6; padding: 8px 14px; margin: 14px 0; }
.notice pre { white-space: pre-wrap; font-size: 12px; }
.missing { color: #8a5a00; font-style: italic; }
.muted { color: #666; }
nav { background: #f6f8fa; border: 1px solid #dde3ea; padding: 4px 16px; margin: 14px 0; }
nav li { margin: 2px 0; }
nav .sub a { font-size: 12.5px; margin-right: 8px; }
details { margin: 4px 0 14px; }
summary { cursor: pointer; color: #2a5d8f; }
</style>
)";

// Counts the plots that rendered once the page has loaded (see report_html.h).
constexpr char kScript[] = R"(<script>
window.addEventListener('load', function () {
  var plots = document.querySelectorAll('img.plot');
  var loaded = 0;
  for (var i = 0; i < plots.length; ++i) {
    if (plots[i].complete && plots[i].naturalWidth > 0) ++loaded;
  }
  document.body.dataset.plotsLoaded = String(loaded);
  document.body.dataset.plotsTotal = String(plots.length);
  var status = document.getElementById('plot-status');
  if (status) status.textContent = loaded + ' of ' + plots.length + ' plots shown.';
});
</script>
)";

constexpr char kFigureMark[] = "<!--figure:";
constexpr char kNoticeMark[] = "<!--notice-->";

// The page under construction: HTML with a mark where each figure goes, and the figures.
class ReportPage {
 public:
  std::ostringstream html;

  void AddFigure(Figure figure, const std::string& alt) {
    html << kFigureMark << figures_.size() << "-->\n";
    figures_.push_back(std::move(figure));
    alts_.push_back(alt);
  }

  // Draws the figures and puts them (or a note that they are missing) in place of the marks.
  std::string Finish(double* plot_seconds) {
    const SteadyClock::time_point start = SteadyClock::now();
    const FigureRendering rendering = RenderFigures(figures_);
    *plot_seconds = SecondsSince(start);
    const std::string text = html.str();
    size_t svg_bytes = 0;
    for (const std::string& svg : rendering.svg) svg_bytes += svg.size();
    std::string out;
    out.reserve(text.size() + svg_bytes / 3 * 4 + 4 * figures_.size() + 1024);
    size_t at = 0;
    for (size_t mark; (mark = text.find(kFigureMark, at)) != std::string::npos;) {
      out.append(text, at, mark - at);
      const size_t begin = mark + sizeof(kFigureMark) - 1, end = text.find("-->", begin);
      const size_t index = std::stoul(text.substr(begin, end - begin));
      out += Image(index, rendering.svg[index]);
      at = end + 3;
    }
    out.append(text, at, std::string::npos);
    const size_t notice = out.find(kNoticeMark);
    if (notice != std::string::npos) {
      out.replace(notice, sizeof(kNoticeMark) - 1, Notice(rendering));
    }
    return out;
  }

 private:
  std::string Image(size_t index, const std::string& svg) const {
    const Figure& f = figures_[index];
    if (svg.empty()) {
      return "<p class=\"missing\">Plot " + HtmlEscape(f.name) +
             " not drawn (see the notice at the top).</p>";
    }
    return "<img class=\"plot\" data-plot=\"" + HtmlEscape(f.name) + "\" alt=\"" +
           HtmlEscape(alts_[index]) + "\" width=\"" + std::to_string(f.width) + "\" height=\"" +
           std::to_string(f.height) + "\" src=\"data:image/svg+xml;base64," + Base64Encode(svg) +
           "\">";
  }

  std::string Notice(const FigureRendering& rendering) const {
    if (rendering.error.empty()) return "";
    size_t drawn = 0;
    for (const std::string& svg : rendering.svg) drawn += svg.empty() ? 0 : 1;
    return "<div class=\"notice\"><p><strong>" +
           std::string(drawn == 0 ? "No plots: " : "Some plots are missing: ") +
           "</strong>plots are drawn by gnuplot (Debian package gnuplot-nox), which reported:"
           "</p>\n<pre>" +
           HtmlEscape(rendering.error) + "</pre></div>\n";
  }

  std::vector<Figure> figures_;
  std::vector<std::string> alts_;
};

// Angle outputs some experiment compares modulo one turn: plotted on one turn too.
std::vector<std::string> AngleOutputs(const RunConfig& config) {
  std::vector<std::string> angles;
  for (const ExperimentSpec& e : config.experiments) {
    for (const std::string& output : e.wrapped_outputs) {
      if (std::find(angles.begin(), angles.end(), output) == angles.end()) {
        angles.push_back(output);
      }
    }
  }
  return angles;
}

// Records of one list of fits drawn as figures at most: a campaign of thousands of records
// draws those that fit worst (each figure is a gnuplot run and an image in the page); every
// record keeps its table, and its trace in traces/.
constexpr size_t kMaxRecordFigures = 12;

// The records of `groups` to draw: all, or the kMaxRecordFigures whose worst piece has the
// largest rms cost (a diverged one first).
std::vector<bool> RecordsToDraw(const std::vector<std::vector<const ExperimentFit*>>& groups) {
  std::vector<bool> draw(groups.size(), groups.size() <= kMaxRecordFigures);
  if (groups.size() <= kMaxRecordFigures) return draw;
  std::vector<double> worst(groups.size(), 0.0);
  for (size_t g = 0; g < groups.size(); ++g) {
    for (const ExperimentFit* fit : groups[g]) {
      worst[g] = std::max(worst[g], fit->diverged || !std::isfinite(fit->rms_cost)
                                        ? std::numeric_limits<double>::infinity()
                                        : fit->rms_cost);
    }
  }
  std::vector<size_t> order(groups.size());
  for (size_t g = 0; g < order.size(); ++g) order[g] = g;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return worst[a] > worst[b]; });
  for (size_t k = 0; k < kMaxRecordFigures; ++k) draw[order[k]] = true;
  return draw;
}

// A figure and metrics table per record of `fits`, in the units the user reads
// (display_units.h), and its x-y track where the model has horizontal positions; regression
// fits get their table only.
void FitFigures(const RunConfig& config, const std::string& key, const std::string& what,
                const std::vector<ExperimentFit>& fits, const std::vector<std::string>& angles,
                ReportPage* page) {
  const ModelInfo& info = config.model->info();
  const std::pair<int, int> track = info.TrackOutputs();
  const std::vector<std::vector<const ExperimentFit*>> groups = GroupByRecord(fits);
  const std::vector<bool> draw = RecordsToDraw(groups);
  if (groups.size() > kMaxRecordFigures) {
    page->html << "<p class=\"muted\">" << groups.size() << " records: figures for the "
               << kMaxRecordFigures
               << " that fit worst (largest rms cost); every record's table below, and its "
                  "measured and simulated outputs in traces/.</p>\n";
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::vector<const ExperimentFit*>& group = groups[g];
    const std::string record = RecordName(group.front()->experiment);
    page->html << "<h4>" << HtmlEscape(record);
    if (group.size() > 1) {
      page->html << " <span class=\"muted\">(" << group.size() << " segments)</span>";
    }
    page->html << "</h4>\n";
    std::map<std::string, DisplayUnit> units;
    for (const std::string& output : info.outputs) {
      units[output] = OutputDisplayUnit(config, record, output);
    }
    Figure figure;
    if (draw[g] && IsSimulationFit(*group.front()) &&
        TraceFigure(key + "." + record, group, angles, units, &figure)) {
      page->AddFigure(std::move(figure), record + ": measured and simulated outputs, " + what);
    }
    if (draw[g] && track.first >= 0 && IsSimulationFit(*group.front()) &&
        TrackFigure(key + "." + record + ".track", group, info.outputs[track.first],
                    info.outputs[track.second], &figure)) {
      page->AddFigure(std::move(figure), record + ": x-y track, measured and simulated, " + what);
    }
    page->html << MetricsTable(group, &config);
  }
}

std::vector<std::string> SharedNames(const StageResult& stage, std::vector<int>* index) {
  std::vector<std::string> names;
  for (size_t k = 0; k < stage.correlation_names.size(); ++k) {
    if (stage.correlation_names[k].find('[') != std::string::npos) continue;
    names.push_back(stage.correlation_names[k]);
    index->push_back(static_cast<int>(k));
  }
  return names;
}

// Whiteness and input correlation of the fit's residuals: a table, and MATLAB resid's plots of
// the few worst channels.
void ResidualSection(const StageResult& stage, const std::string& id, const std::string& key,
                     ReportPage* page) {
  if (stage.residuals.empty()) return;
  page->html << "<h3 id=\"" << id << "-residuals\">Residual analysis</h3>\n"
             << ResidualTableHtml(stage.residuals);
  constexpr size_t kPlotted = 4;
  Figure figure;
  for (const ResidualAnalysis* a : ResidualsToPlot(stage.residuals, kPlotted)) {
    if (ResidualFigure(key + ".residuals." + a->experiment + "." + a->output, *a, &figure)) {
      page->AddFigure(std::move(figure), "residual autocorrelation and cross-correlation, " +
                                             a->experiment + " " + a->output + ", stage " +
                                             stage.name);
    }
  }
}

void StageSection(const RunConfig& config, const StageResult& stage, size_t number,
                  ReportPage* page) {
  const StageSummary& s = stage.summary;
  const std::string id = "stage-" + std::to_string(number);
  const std::string key = "stage" + std::to_string(number);
  std::ostringstream& html = page->html;
  html << "<section id=\"" << id << "\">\n<h2>Stage " << number << ": " << HtmlEscape(stage.name)
       << "</h2>\n<p class=\"brief\">" << HtmlEscape(s.BriefReport()) << "</p>\n";
  const bool solved = s.chosen >= 0 && s.chosen < static_cast<int>(s.refinements.size());
  html << "<table>\n<tr><th>model</th><th>cost</th><th>iterations</th><th>termination</th>"
          "<th>refinements</th><th>time [s]</th></tr>\n<tr><td>"
       << HtmlEscape(stage.model) << "</td><td class=\"num\">"
       << (solved ? HtmlNumber(s.local().final_cost, "%.6e") : "—") << "</td><td class=\"num\">"
       << (solved ? std::to_string(s.local().iterations) : "—") << "</td><td>"
       << (solved ? HtmlEscape(s.local().termination) : "—") << "</td><td class=\"num\">"
       << s.refinements.size() << "</td><td class=\"num\">" << HtmlNumber(s.time_seconds, "%.3f")
       << "</td></tr>\n</table>\n<p>" << HtmlEscape(DescribeCounts(CountUnknowns(stage.estimates)))
       << ".</p>\n";
  if (s.global.run) html << "<p>" << HtmlEscape(s.global.BriefReport()) << "</p>\n";
  html << "<p class=\"verdict " << VerdictToString(stage.verdict) << "\">"
       << HtmlEscape(VerdictLine(stage.verdict, stage.findings));
  if (std::isfinite(stage.comparable_cost)) {
    html << "; comparable cost (configured weights) " << HtmlNumber(stage.comparable_cost, "%.6e");
  }
  html << "</p>\n" << FindingsHtml(stage.findings);
  std::vector<std::string> notes = s.notes;
  if (!s.uncertainty.available && !s.uncertainty.message.empty()) {
    notes.push_back("uncertainty: " + s.uncertainty.message);
  }
  if (s.uncertainty.available) {
    notes.push_back("uncertainty: standard errors by " + s.uncertainty.method +
                    (s.uncertainty.method_reason.empty() ? ""
                                                         : " (" + s.uncertainty.method_reason + ")"));
  }
  for (const std::string& d : s.uncertainty.undetermined) notes.push_back("undetermined: " + d);
  if (stage.held_out.done) {
    notes.push_back("held-out check against the stage's start: " + DescribeHeldOut(stage.held_out) +
                    (stage.held_out.worse ? " (worse)" : " (not worse)"));
  }
  if (!notes.empty()) {
    html << "<ul class=\"notes\">\n";
    for (const std::string& note : notes) html << "<li>" << HtmlEscape(note) << "</li>\n";
    html << "</ul>\n";
  }
  const std::vector<std::string> angles = AngleOutputs(config);
  html << "<h3 id=\"" << id << "-fit\">Fit: measured vs simulated</h3>\n";
  if (s.fits.size() > 1 && IsSimulationFit(s.fits.front())) {
    html << RunFitTableHtml(PerRunFits(config, s.fits));
  }
  FitFigures(config, key + ".fit", "stage " + stage.name, s.fits, angles, page);

  ResidualSection(stage, id, key, page);
  html << "<h3 id=\"" << id << "-parameters\">Estimates</h3>\n"
       << EstimatesTables(stage.estimates, &config);
  html << BootstrapHtml(stage);
  html << NoiseModelHtml(config, stage);

  std::vector<int> index;
  const std::vector<std::string> names = SharedNames(stage, &index);
  Figure figure;
  if (names.size() >= 2) {
    Eigen::MatrixXd shared(names.size(), names.size());
    for (size_t r = 0; r < names.size(); ++r) {
      for (size_t c = 0; c < names.size(); ++c)
        shared(r, c) = stage.correlation(index[r], index[c]);
    }
    if (CorrelationFigure(key + ".correlation", names, shared, &figure)) {
      html << "<h3 id=\"" << id << "-correlation\">Correlation of the estimates</h3>\n";
      if (names.size() < stage.correlation_names.size()) {
        html << "<p class=\"muted\">Shared parameters only; the "
             << stage.correlation_names.size() - names.size()
             << " per-experiment unknowns are left out.</p>\n";
      }
      page->AddFigure(std::move(figure), "correlation matrix, stage " + stage.name);
    }
  }
  if (CostHistoryFigure(key + ".cost", s, &figure)) {
    html << "<h3 id=\"" << id << "-cost\">Cost history</h3>\n";
    page->AddFigure(std::move(figure), "cost history, stage " + stage.name);
  }
  if (!stage.validation.empty() || !stage.velocity_validation.empty()) {
    html << "<h3 id=\"" << id << "-validation\">Validation on held-out experiments</h3>\n"
         << HeldOutStartHtml(stage.validation);
    if (stage.validation.size() > 1) html << RunFitTableHtml(PerRunFits(config, stage.validation));
    FitFigures(config, key + ".validation", "held out, stage " + stage.name, stage.validation,
               angles, page);
    if (!stage.validation_residuals.empty()) {
      html << "<h4>Residual analysis of the held-out runs</h4>\n"
           << ResidualTableHtml(stage.validation_residuals);
    }
    html << HeldOutParametersHtml(stage.held_out_parameters, stage.validation,
                                 ParameterUnits(config));
    if (!stage.velocity_validation.empty()) {
      html << "<h4>Velocities (data: Savitzky-Golay reconstruction)</h4>\n"
           << VelocityTable(stage.velocity_validation);
    }
  }
  if (stage.step_regression) {
    const StepRegressionReport& r = *stage.step_regression;
    html << "<h3 id=\"" << id << "-regression\">Step regression</h3>\n" << StepRegressionTables(r);
    if (LassoPathFigure(key + ".lasso", r, &figure)) {
      html << "<h4>Lasso paths: leave-one-group-out CV error</h4>\n";
      page->AddFigure(std::move(figure), "lasso CV paths, stage " + stage.name);
    }
    std::vector<std::string> states = {"x_0", "x_1"};
    int asymptote = 0;
    if (const DampingInertiaForm* form = config.model->damping_inertia_form()) {
      const ModelInfo& info = config.model->info();
      if (form->states.size() == 2)
        states = {info.states[form->states[0]], info.states[form->states[1]]};
      asymptote = form->asymptote_state;
    }
    if (StepSamplesFigure(key + ".samples", r, states, asymptote, &figure)) {
      html << "<h4>Damping and inertia samples</h4>\n";
      page->AddFigure(std::move(figure), "step samples, stage " + stage.name);
    }
  }
  html << "</section>\n";
}

void FinalSection(const RunConfig& config, const RunResult& result, ReportPage* page) {
  std::ostringstream& html = page->html;
  html << "<section id=\"final\">\n<h2>Final parameters</h2>\n<p>Shared parameters fused over "
          "their stages by the <strong>"
       << HtmlEscape(FusionRuleToString(config.fusion))
       << "</strong> rule; isolated and free ones from the last stage that estimated them. Their "
          "values and intervals are in the <a href=\"#summary-parameters\">summary</a>.</p>\n";
  std::vector<Finding> doubts;
  for (const Finding& f : result.findings) {
    if (f.stage == "final") doubts.push_back(f);
  }
  if (doubts.empty()) {
    html << "<p>The final values are admissible"
         << (result.final_validation.empty() ? "" : " and predict the held-out data") << ".</p>\n";
  } else {
    html << FindingsHtml(doubts);
  }
  if (!result.final_validation.empty() || !result.final_velocity_validation.empty()) {
    html << "<h3 id=\"final-validation\">Final validation</h3>\n"
         << HeldOutStartHtml(result.final_validation);
    if (result.reference_check.done) {
      html << "<p>Against the reference model (" << HtmlEscape(config.final_validation.reference.folder)
           << "): "
           << HtmlEscape(DescribeReferenceCheck(result, OutputUnits(config)))
           << (result.reference_check.worse ? " (worse)" : " (not worse)") << ".</p>\n";
    }
    if (result.final_validation.size() > 1) {
      html << RunFitTableHtml(PerRunFits(config, result.final_validation));
    }
    FitFigures(config, "final.validation", "final values", result.final_validation,
               AngleOutputs(config), page);
    if (!result.final_validation_residuals.empty()) {
      html << "<h4>Residual analysis of the held-out runs</h4>\n"
           << ResidualTableHtml(result.final_validation_residuals);
    }
    html << HeldOutParametersHtml(result.final_held_out_parameters, result.final_validation,
                                 ParameterUnits(config));
    if (!result.final_velocity_validation.empty()) {
      html << "<h4>Velocities</h4>\n" << VelocityTable(result.final_velocity_validation);
    }
  }
  html << "</section>\n";
}

void Contents(const RunResult& result, std::ostringstream* html) {
  *html << "<nav><h3>Contents</h3>\n<ol>\n<li><a href=\"#summary\">Summary</a> <span "
           "class=\"sub\"><a href=\"#summary-parameters\">final parameters</a><a "
           "href=\"#summary-fit\">fit per run</a><a href=\"#warnings\">warnings</a></span></li>\n";
  for (size_t k = 0; k < result.stages.size(); ++k) {
    const StageResult& stage = result.stages[k];
    const std::string id = "stage-" + std::to_string(k + 1);
    *html << "<li><a href=\"#" << id << "\">Stage " << k + 1 << ": " << HtmlEscape(stage.name)
          << "</a> <span class=\"sub\"><a href=\"#" << id << "-fit\">fit</a><a href=\"#" << id
          << "-parameters\">estimates</a>";
    if (!stage.residuals.empty()) *html << "<a href=\"#" << id << "-residuals\">residuals</a>";
    if (!stage.validation.empty() || !stage.velocity_validation.empty()) {
      *html << "<a href=\"#" << id << "-validation\">validation</a>";
    }
    if (stage.step_regression) *html << "<a href=\"#" << id << "-regression\">regression</a>";
    *html << "</span></li>\n";
  }
  *html << "<li><a href=\"#final\">Final parameters</a>";
  if (!result.final_validation.empty() || !result.final_velocity_validation.empty()) {
    *html << " <span class=\"sub\"><a href=\"#final-validation\">validation</a></span>";
  }
  if (!result.zigzags.empty()) *html << "</li>\n<li><a href=\"#zigzag\">Zigzag figures</a>";
  if (result.selection) *html << "</li>\n<li><a href=\"#selection\">Structure selection</a>";
  if (!result.turning_circles.empty()) {
    *html << "</li>\n<li><a href=\"#turning\">Turning circles</a>";
  }
  *html << "</li>\n<li><a href=\"#papers\">Paper-style tables</a> <span class=\"sub\">"
           "<a href=\"#paper-parameters\">parameters by stage</a><a href=\"#paper-cost\">cost "
           "per test</a><a href=\"#paper-validation\">validation fit %</a></span></li>\n"
           "</ol>\n</nav>\n";
}

}  // namespace

std::string RunReportHtml(const RunConfig& config, const RunResult& result) {
  const SteadyClock::time_point start = SteadyClock::now();
  ReportPage page;
  std::ostringstream& html = page.html;
  const std::string model = config.model->info().name;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<title>vesselid run: " << HtmlEscape(config.path) << "</title>\n"
       << kStyle << "</head>\n<body>\n<h1>vesselid run report</h1>\n<table>\n"
       << "<tr><th>config</th><td>" << HtmlEscape(config.path) << "</td></tr>\n";
  if (!config.description.empty()) {
    html << "<tr><th>description</th><td>" << HtmlEscape(config.description) << "</td></tr>\n";
  }
  html << "<tr><th>model</th><td>" << HtmlEscape(config.family) << " / " << HtmlEscape(model)
       << "</td></tr>\n<tr><th>stages</th><td>" << result.stages.size()
       << "</td></tr>\n<tr><th>run time</th><td>" << HtmlNumber(result.time_seconds, "%.2f")
       << " s</td></tr>\n</table>\n<p id=\"plot-status\" class=\"muted\"></p>\n"
       << kNoticeMark << "\n";
  if (!result.stopped_stage.empty()) {
    html << "<p class=\"warning\"><strong>The run stopped in stage '"
         << HtmlEscape(result.stopped_stage) << "'</strong>: " << HtmlEscape(result.stop_message)
         << "</p>\n";
  }
  Contents(result, &html);
  html << SummarySectionHtml(config, result);
  for (size_t k = 0; k < result.stages.size(); ++k) {
    StageSection(config, result.stages[k], k + 1, &page);
  }
  FinalSection(config, result, &page);
  html << ZigzagRunsHtml(result.zigzags) << TurningRunsHtml(result.turning_circles);
  if (result.selection) html << SelectionHtml(*result.selection);
  html << "<section id=\"papers\">\n<h2>Paper-style tables</h2>\n"
       << PaperTables(config, result) << "</section>\n";
  html << "<p class=\"muted\">Report written in <!--seconds--> s (plots <!--plot-seconds--> s)."
          "</p>\n"
       << kScript << kSortScript << "</body>\n</html>\n";
  double plot_seconds = 0.0;
  std::string out = page.Finish(&plot_seconds);
  auto fill = [&out](const std::string& mark, double value) {
    const size_t at = out.rfind(mark);
    if (at != std::string::npos) out.replace(at, mark.size(), HtmlNumber(value, "%.2f"));
  };
  fill("<!--plot-seconds-->", plot_seconds);
  fill("<!--seconds-->", SecondsSince(start));
  return out;
}

bool WriteRunReport(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                    std::string* error) {
  return WriteFileAtomically((std::filesystem::path(out_dir) / "report.html").string(),
                             RunReportHtml(config, result), error);
}

}  // namespace vesselid
