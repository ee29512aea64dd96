#include "engine/report/residual_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/diagnose/residual_findings.h"
#include "engine/output/residual_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {
namespace {

constexpr size_t kTableRowsMax = 40;

}  // namespace

std::vector<const ResidualAnalysis*> ResidualsToPlot(const std::vector<ResidualAnalysis>& analyses,
                                                     size_t count) {
  std::vector<const ResidualAnalysis*> list = ResidualsWorstFirst(analyses);
  list.erase(std::remove_if(list.begin(), list.end(),
                            [](const ResidualAnalysis* a) { return !a->tested(); }),
             list.end());
  if (list.size() > count) list.resize(count);
  return list;
}

bool ResidualFigure(const std::string& name, const ResidualAnalysis& a, Figure* figure) {
  if (!a.tested()) return false;
  const int panels = 1 + static_cast<int>(a.cross_correlation.size());
  constexpr int kPanel = 190, kTop = 16, kGap = 56;
  *figure = Figure();
  figure->name = name;
  figure->width = 760;
  figure->height = kTop + panels * (kPanel + kGap);
  const PlotFrame frame{figure->width, figure->height};
  char line[96];
  std::string acf;
  for (int k = 1; k <= a.lags; ++k) {  // r_0 = 1 would flatten the rest
    std::snprintf(line, sizeof(line), "%d %s\n", k, GnuplotNumber(a.autocorrelation[k]).c_str());
    acf += line;
  }
  figure->data.push_back(acf);
  for (const ResidualCrossCorrelation& c : a.cross_correlation) {
    std::string data;
    for (int k = -a.lags; k <= a.lags; ++k) {
      std::snprintf(line, sizeof(line), "%d %s\n", k, GnuplotNumber(c.values[k + a.lags]).c_str());
      data += line;
    }
    figure->data.push_back(data);
  }
  // A panel: impulses of D<file> over [low, high] lags, the band +-band as dashed lines; the
  // y range symmetric around the largest |value| (or twice the band), at most +-1.
  auto panel = [&](int index, int file, int low, int high, double band, const std::string& title,
                   const std::string& xlabel, const std::vector<double>& values) {
    double largest = 2.0 * band;
    for (double v : values) {
      if (std::isfinite(v)) largest = std::max(largest, 1.15 * std::abs(v));
    }
    const double range = std::min(1.05, largest);
    std::ostringstream p;
    const double top = kTop + index * (kPanel + kGap) + 22;
    p << frame.Area(70, figure->width - 20, top, top + kPanel - 22) << "set title "
      << GnuplotString(title) << " font ',11'\n"
      << "set xlabel " << GnuplotString(xlabel) << " offset 0,0.6\n"
      << "set xrange [" << low - 0.5 << ":" << high + 0.5 << "]\nset yrange ["
      << GnuplotNumber(-range) << ":" << GnuplotNumber(range) << "]\n"
      << "set ytics autofreq\nset xtics autofreq\n"
      << "plot D" << file << " using 1:2 with impulses lw 2 lc rgb '#1f77b4' notitle, "
      << GnuplotNumber(band) << " with lines dt 2 lw 1.4 lc rgb '#c0392b' title '99 % band', "
      << GnuplotNumber(-band) << " with lines dt 2 lw 1.4 lc rgb '#c0392b' notitle, "
      << "0 with lines lw 1 lc rgb '#606060' notitle\n";
    return p.str();
  };
  std::ostringstream s;
  s << kPlotStyle << "set key top right font ',10'\nset tics font ',10'\nset multiplot\n"
    << "set samples 2\n";
  const std::vector<double> r(a.autocorrelation.begin() + 1, a.autocorrelation.end());
  s << panel(0, 0, 0, a.lags, a.band_99,
             "autocorrelation of the residuals of " + a.output + ", " + a.experiment + " (" +
                 DescribeResiduals(a) + ")",
             "lag [samples] (r_0 = 1 not drawn)", r);
  for (size_t i = 0; i < a.cross_correlation.size(); ++i) {
    const ResidualCrossCorrelation& c = a.cross_correlation[i];
    s << panel(static_cast<int>(i) + 1, static_cast<int>(i) + 1, -a.lags, a.lags, c.band_99,
               "cross-correlation of the residuals with " + c.input +
                   (c.correlated ? " (beyond the band at lags >= 0)" : ""),
               "lag [samples] (> 0: " + c.input + " leads)", c.values);
  }
  s << "unset multiplot\n";
  figure->script = s.str();
  return true;
}

std::string ResidualTableHtml(const std::vector<ResidualAnalysis>& analyses) {
  std::ostringstream html;
  int white = 0, tested = 0, correlated = 0;
  for (const ResidualAnalysis& a : analyses) {
    tested += a.tested();
    white += a.tested() && a.white;
    correlated += a.input_correlated;
  }
  html << "<p>Residuals e = simulated - measured, per experiment and output: " << white << " of "
       << tested << " channel(s) white (Ljung-Box p &ge; " << kWhitenessLevel
       << " over L = min(25, N/5) lags), " << correlated
       << " correlated with past inputs beyond the 99 % band. Coloured residuals make the "
          "Hessian standard errors too narrow.</p>\n";
  const std::vector<const ResidualAnalysis*> list = ResidualsWorstFirst(analyses);
  if (list.size() > kTableRowsMax) {
    html << "<p class=\"muted\">The " << kTableRowsMax << " worst of " << list.size()
         << " channels.</p>\n";
  }
  html << "<div class=\"scroll\"><table class=\"sortable\">\n<thead><tr>" << Th("experiment")
       << Th("output") << Th("samples") << Th("lags") << Th("lag-1") << Th("Ljung-Box Q") << Th("p")
       << Th("verdict") << "</tr></thead>\n<tbody>\n";
  for (size_t i = 0; i < list.size() && i < kTableRowsMax; ++i) {
    const ResidualAnalysis& a = *list[i];
    const bool flagged = a.tested() && (!a.white || a.input_correlated);
    html << (flagged ? "<tr class=\"flagged\">" : "<tr>") << Td(a.experiment) << Td(a.output)
         << Num(std::to_string(a.samples)) << Num(std::to_string(a.lags))
         << Num(HtmlNumber(a.lag1, "%.3f")) << Num(HtmlNumber(a.ljung_box_q, "%.4g"))
         << Num(a.ljung_box_p < 1e-16 ? "< 1e-16" : HtmlNumber(a.ljung_box_p, "%.2g"))
         << Td(DescribeResiduals(a)) << "</tr>\n";
  }
  html << "</tbody>\n</table></div>\n";
  return html.str();
}

}  // namespace vesselid
