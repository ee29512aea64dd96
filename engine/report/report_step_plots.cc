// Figures of step-regression stages (report_plots.h): lasso CV paths and step samples.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "engine/report/report_plots.h"

namespace vesselid {
namespace {

std::string TermName(const StepRegressionReport& report, size_t k, const char* fallback) {
  return k < report.terms.size() ? report.terms[k].name : std::string(fallback);
}

// A figure of n panels, two to a row, and the start of its gnuplot commands.
void StartPanelGrid(const std::string& name, int n, Figure* figure, std::ostringstream* s) {
  const int cols = n > 1 ? 2 : 1, rows = (n + cols - 1) / cols;
  *figure = Figure();
  figure->name = name;
  figure->width = cols == 2 ? 1100 : 620;
  figure->height = rows * 300;
  *s << kPlotStyle << "set multiplot layout " << rows << "," << cols << "\n";
}

struct SamplePanel {
  std::string title, x_label, y_label;
  SeriesPiece measured, mirrored;
};

}  // namespace

bool LassoPathFigure(const std::string& name, const StepRegressionReport& report, Figure* figure) {
  if (report.terms.empty()) return false;
  const int n = static_cast<int>(report.terms.size());
  std::ostringstream s;
  StartPanelGrid(name, n, figure, &s);
  s << "set logscale xy\nset format x '%.0e'\nset format y '%.1e'\n"
    << "set xlabel 'lambda'\nset ylabel 'CV error'\nset key top left font ',10'\n"
    << "set offsets 0, 0, graph 0.3, 0\n";  // headroom: the key stays off the data
  for (int k = 0; k < n; ++k) {
    const TermRegression& t = report.terms[k];
    const LassoPath& path = t.path;
    double smallest = std::numeric_limits<double>::infinity();
    for (double cv : path.cv_error) {
      if (std::isfinite(cv) && cv > 0) smallest = std::min(smallest, cv);
    }
    // Band cv +- SE, its lower edge clipped at half the smallest CV error (log axis).
    std::string data;
    char line[128];
    for (size_t p = 0; p < path.lambda.size() && p < path.cv_error.size(); ++p) {
      const double lambda = path.lambda[p], cv = path.cv_error[p];
      const double se = p < path.cv_standard_error.size() ? path.cv_standard_error[p] : 0.0;
      if (!(lambda > 0) || !(cv > 0) || !std::isfinite(lambda) || !std::isfinite(cv)) continue;
      const double spread = std::isfinite(se) ? se : 0.0;
      std::snprintf(line, sizeof(line), "%.9g %.9g %.9g %.9g\n", lambda, cv,
                    std::max(cv - spread, 0.5 * smallest), cv + spread);
      data += line;
    }
    s << "set title " << GnuplotString(t.name) << " font ',11'\n";
    if (data.empty()) {
      s << "unset logscale xy\nset label 1 'no path' at graph 0.5, graph 0.5 center\n"
        << "plot [0:1][0:1] NaN notitle\nunset label 1\nset logscale xy\n";
      continue;
    }
    figure->data.push_back(data);
    const std::string file = "D" + std::to_string(figure->data.size() - 1);
    s << "set arrow 1 from " << GnuplotNumber(t.lambda) << ", graph 0 to "
      << GnuplotNumber(t.lambda) << ", graph 1 nohead dt 2 lw 1.5 lc rgb '#d62728'\n"
      << "plot " << file
      << " using 1:3:4 with filledcurves fc rgb '#c6dbef' fs solid 1.0 title '±1 SE', " << file
      << " using 1:2 with linespoints lw 1.5 pt 7 ps 0.5 lc rgb '#08519c' title 'CV error', "
      << "NaN with lines dt 2 lw 1.5 lc rgb '#d62728' title 'chosen lambda'\n"
      << "unset arrow 1\n";
  }
  figure->script = s.str();
  return true;
}

bool StepSamplesFigure(const std::string& name, const StepRegressionReport& report,
                       const std::vector<std::string>& states, int asymptote_state,
                       Figure* figure) {
  const StepSamples& samples = report.samples;
  const char* kDefaults[] = {"sigma_0", "sigma_1", "m_0", "m_1"};
  const int xs = std::clamp(asymptote_state, 0, 1);
  std::vector<SamplePanel> panels(4);
  for (int i = 0; i < 2; ++i) {
    SamplePanel& d = panels[i];
    d.title = "damping samples: " + TermName(report, i, kDefaults[i]);
    d.x_label = states[i];
    d.y_label = TermName(report, i, kDefaults[i]);
    for (const DampingSample& sample : samples.damping) {
      SeriesPiece& piece = sample.mirrored ? d.mirrored : d.measured;
      piece.x.push_back(sample.x[i]);
      piece.y.push_back(sample.sigma[i]);
    }
    SamplePanel& m = panels[2 + i];
    m.title = "inertia samples: " + TermName(report, 2 + i, kDefaults[2 + i]);
    m.x_label = states[xs];
    m.y_label = TermName(report, 2 + i, kDefaults[2 + i]);
    for (const InertiaSample& sample : samples.inertia[i]) {
      SeriesPiece& piece = sample.mirrored ? m.mirrored : m.measured;
      piece.x.push_back(sample.x[xs]);
      piece.y.push_back(sample.inertia);
    }
  }
  panels.erase(std::remove_if(panels.begin(), panels.end(),
                              [](const SamplePanel& p) {
                                return p.measured.y.empty() && p.mirrored.y.empty();
                              }),
               panels.end());
  if (panels.empty()) return false;
  std::ostringstream s;
  StartPanelGrid(name, static_cast<int>(panels.size()), figure, &s);
  s << "set key top left font ',10'\nset offsets 0, 0, graph 0.3, 0\n";
  // Scatter data are few (hundreds): written whole, not decimated.
  const size_t kAll = std::numeric_limits<size_t>::max();
  for (const SamplePanel& p : panels) {
    s << "set title " << GnuplotString(p.title) << " font ',11'\n"
      << "set xlabel " << GnuplotString(p.x_label) << "\nset ylabel " << GnuplotString(p.y_label)
      << "\nplot ";
    bool first = true;
    if (!p.measured.y.empty()) {
      figure->data.push_back(SeriesData({p.measured}, kAll));
      s << "D" << figure->data.size() - 1
        << " using 1:2 with points pt 7 ps 0.6 lc rgb '#1f77b4' title 'from the records'";
      first = false;
    }
    if (!p.mirrored.y.empty()) {
      figure->data.push_back(SeriesData({p.mirrored}, kAll));
      s << (first ? "" : ", ") << "D" << figure->data.size() - 1
        << " using 1:2 with points pt 6 ps 0.6 lc rgb '#ff7f0e' title 'mirrored copies'";
    }
    s << "\n";
  }
  figure->script = s.str();
  return true;
}

}  // namespace vesselid
