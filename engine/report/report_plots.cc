#include "engine/report/report_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "engine/base/text_match.h"
#include "engine/model/model.h"

namespace vesselid {
namespace {

// Trace figure geometry, pixels: a key band on top, a row per channel, the time label below.
constexpr int kTraceWidth = 1100;
constexpr int kKeyBand = 24;
constexpr int kRowHeight = 180;
constexpr int kTimeLabel = 20;
constexpr double kSignalLeft = 78, kSignalRight = 700, kResidualLeft = 790, kResidualRight = 1085;

struct ChannelSeries {
  std::string output;
  std::vector<SeriesPiece> measured, simulated, residual;
  bool any_measured = false;
};

ChannelSeries* FindChannel(std::vector<ChannelSeries>* channels, const std::string& output) {
  for (ChannelSeries& c : *channels) {
    if (c.output == output) return &c;
  }
  channels->push_back({output, {}, {}, {}, false});
  return &channels->back();
}

// "plot" arguments of the non-empty series among files[k] (with their styles).
std::string PlotList(const std::vector<std::pair<int, std::string>>& items) {
  std::string out;
  for (const auto& [file, style] : items) {
    if (file < 0) continue;
    out += (out.empty() ? "plot " : ", ") + ("D" + std::to_string(file)) + " using 1:2 " + style;
  }
  return out;
}

// Appends `piece` to `pieces`, cut where consecutive values jump by more than pi (an angle
// wrapping around), so that no line is drawn across the wrap.
void AppendAngle(const SeriesPiece& piece, std::vector<SeriesPiece>* pieces) {
  SeriesPiece part;
  for (size_t k = 0; k < piece.y.size(); ++k) {
    if (k > 0 && std::abs(piece.y[k] - piece.y[k - 1]) > M_PI) {
      pieces->push_back(std::move(part));
      part = SeriesPiece();
    }
    part.x.push_back(piece.x[k]);
    part.y.push_back(piece.y[k]);
  }
  pieces->push_back(std::move(part));
}

// Range of the values of a series' pieces (low > high when empty).
void Extend(const std::vector<SeriesPiece>& pieces, double* low, double* high) {
  for (const SeriesPiece& p : pieces) {
    for (double v : p.y) {
      *low = std::min(*low, v);
      *high = std::max(*high, v);
    }
  }
}

// "set <axis>tics <step>" for about `count` + 1 tics over [low, high] (1, 2 or 5 times a power
// of ten); "set <axis>tics autofreq" when the range is empty.
std::string TicStep(const char* axis, double low, double high, int count) {
  const double range = high - low;
  const std::string command = std::string("set ") + axis + "tics ";
  if (!(range > 0) || !std::isfinite(range)) return command + "autofreq\n";
  const double raw = range / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  const double step = (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * magnitude;
  return command + GnuplotNumber(step) + "\n";
}

// A history's positive finite values as (1-based position, value).
SeriesPiece PositiveHistory(const std::vector<double>& history) {
  SeriesPiece piece;
  for (size_t k = 0; k < history.size(); ++k) {
    if (!std::isfinite(history[k]) || history[k] <= 0) continue;
    piece.x.push_back(static_cast<double>(k));
    piece.y.push_back(history[k]);
  }
  return piece;
}

}  // namespace

bool TraceFigure(const std::string& name, const std::vector<const ExperimentFit*>& fits,
                 const std::vector<std::string>& angle_outputs,
                 const std::map<std::string, DisplayUnit>& units, Figure* figure) {
  const std::string kMeasured = "_measured", kSimulated = "_simulated";
  std::vector<ChannelSeries> channels;
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  // Segments end to end: segment i drawn at offset[i] + (t - its first time), a gap between.
  const bool segments = fits.size() > 1;
  std::vector<double> offset(fits.size(), 0.0), starts;
  if (segments) {
    double span = 0.0;
    for (const ExperimentFit* fit : fits) {
      if (!fit->trace.t.empty()) span += fit->trace.t.back() - fit->trace.t.front();
    }
    const double gap = 0.05 * span / static_cast<double>(fits.size() - 1);  // 5 % in all
    double at = 0.0;
    for (size_t i = 0; i < fits.size(); ++i) {
      const std::vector<double>& t = fits[i]->trace.t;
      if (t.empty()) continue;
      offset[i] = at - t.front();
      starts.push_back(at);
      at += t.back() - t.front() + gap;
    }
  }
  for (size_t f = 0; f < fits.size(); ++f) {
    const ExperimentFit* fit = fits[f];
    const Trajectory& trace = fit->trace;
    for (size_t c = 0; c < trace.names.size(); ++c) {
      if (!EndsWith(trace.names[c], kMeasured)) continue;
      const std::string output = trace.names[c].substr(0, trace.names[c].size() - kMeasured.size());
      const int s = trace.Find(output + kSimulated);
      const bool angle =
          std::find(angle_outputs.begin(), angle_outputs.end(), output) != angle_outputs.end();
      SeriesPiece measured, simulated, residual;
      for (size_t k = 0; k < trace.t.size(); ++k) {
        const double t = trace.t[k] + offset[f], y = trace.columns[c][k];
        const double y_sim = s >= 0 ? trace.columns[s][k] : std::nan("");
        if (std::isfinite(y)) {
          measured.x.push_back(t);
          measured.y.push_back(y);
        }
        if (std::isfinite(y_sim)) {
          // An angle on the branch of the measured one, as the fit compares them.
          simulated.x.push_back(t);
          simulated.y.push_back(angle && std::isfinite(y) ? y + WrapAngle(y_sim - y) : y_sim);
        }
        if (std::isfinite(y) && std::isfinite(y_sim)) {
          residual.x.push_back(t);
          residual.y.push_back(angle ? WrapAngle(y - y_sim) : y - y_sim);
        }
        if (std::isfinite(y) || std::isfinite(y_sim)) {
          t_min = std::min(t_min, t);
          t_max = std::max(t_max, t);
        }
      }
      ChannelSeries* channel = FindChannel(&channels, output);
      channel->any_measured = channel->any_measured || !measured.y.empty();
      if (angle) {
        AppendAngle(measured, &channel->measured);
        AppendAngle(simulated, &channel->simulated);
      } else {
        channel->measured.push_back(std::move(measured));
        channel->simulated.push_back(std::move(simulated));
      }
      channel->residual.push_back(std::move(residual));
    }
  }
  channels.erase(std::remove_if(channels.begin(), channels.end(),
                                [](const ChannelSeries& c) { return !c.any_measured; }),
                 channels.end());
  if (channels.empty()) return false;
  for (ChannelSeries& c : channels) {  // computed in radians (wrapping), shown in its unit
    const auto unit = units.find(c.output);
    if (unit == units.end() || unit->second.scale == 1.0) continue;
    for (std::vector<SeriesPiece>* pieces : {&c.measured, &c.simulated, &c.residual}) {
      for (SeriesPiece& p : *pieces) {
        for (double& y : p.y) y *= unit->second.scale;
      }
    }
  }
  if (!(t_max > t_min)) {  // a single time: gnuplot needs a non-empty range
    t_min -= 0.5;
    t_max += 0.5;
  }

  const int rows = static_cast<int>(channels.size());
  *figure = Figure();
  figure->name = name;
  figure->width = kTraceWidth;
  figure->height = kKeyBand + rows * kRowHeight + kTimeLabel;
  const PlotFrame frame{figure->width, figure->height};
  auto add = [&](const std::vector<SeriesPiece>& pieces, size_t max_points) {
    for (const SeriesPiece& p : pieces) {
      if (!p.y.empty()) {
        figure->data.push_back(SeriesData(pieces, max_points));
        return static_cast<int>(figure->data.size()) - 1;
      }
    }
    return -1;
  };
  std::ostringstream s;
  s << kPlotStyle;
  for (size_t i = 1; i < starts.size(); ++i) {  // where each segment after the first begins
    s << "set arrow from " << GnuplotNumber(starts[i]) << ", graph 0 to "
      << GnuplotNumber(starts[i]) << ", graph 1 nohead dt 2 lc rgb '#9a9a9a'\n";
  }
  s << "set multiplot\n"
    << "set xrange [" << GnuplotNumber(t_min) << ":" << GnuplotNumber(t_max) << "]\n"
    << "set format y '%g'\nset format x '%g'\nset tics font ',10'\n";
  const std::string time_label = segments
                                     ? "'t [s], " + std::to_string(starts.size()) +
                                           " segments end to end, each from its own start (dashed)'"
                                     : "'t [s]'";
  for (int r = 0; r < rows; ++r) {
    const ChannelSeries& c = channels[r];
    const auto shown = units.find(c.output);
    const std::string unit = shown == units.end() ? "" : shown->second.unit;
    const int m = add(c.measured, kSignalPoints), sim = add(c.simulated, kSignalPoints),
              e = add(c.residual, kResidualPoints);
    const double top = kKeyBand + r * kRowHeight + 6, bottom = kKeyBand + (r + 1) * kRowHeight - 26;
    const bool last = r + 1 == rows;
    s << "set xlabel " << (last ? time_label + " offset 0,0.6" : "''") << "\n";
    // Signal panel.
    const double inf = std::numeric_limits<double>::infinity();
    double low = inf, high = -inf, e_low = inf, e_high = -inf;
    Extend(c.measured, &low, &high);
    Extend(c.simulated, &low, &high);
    Extend(c.residual, &e_low, &e_high);
    s << frame.Area(kSignalLeft, kSignalRight, top, bottom) << "unset xzeroaxis\n"
      << TicStep("y", low, high, 4) << TicStep("x", t_min, t_max, 8) << "set ylabel "
      << GnuplotString(WithUnit(c.output, unit)) << "\n";
    if (r == 0) {
      s << "set key horizontal right top samplen 2 at screen " << frame.X(kSignalRight)
        << ", screen " << frame.Y(2) << "\n";
    } else {
      s << "unset key\n";
    }
    s << PlotList({{m, "with lines lw 3 lc rgb '#8ec1e6' title 'measured'"},
                   {sim, "with lines lw 1.3 lc rgb '#c41e1e' title 'simulated'"}})
      << "\n";
    if (e < 0) continue;
    // Residual panel.
    s << frame.Area(kResidualLeft, kResidualRight, top, bottom)
      << "set xzeroaxis lt 1 lw 1 lc rgb '#999999'\nset ylabel "
      << GnuplotString(WithUnit("residual", unit)) << "\n"
      << TicStep("y", std::min(e_low, -e_high), std::max(e_high, -e_low), 4)
      << TicStep("x", t_min, t_max, 4);
    if (r == 0) {
      s << "set key horizontal right top samplen 2 at screen " << frame.X(kResidualRight)
        << ", screen " << frame.Y(2) << "\n";
    }
    s << PlotList({{e, "with lines lw 1 lc rgb '#444444' title 'measured − simulated'"}}) << "\n";
  }
  figure->script = s.str();
  return true;
}

bool CorrelationFigure(const std::string& name, const std::vector<std::string>& labels,
                       const Eigen::MatrixXd& correlation, Figure* figure) {
  const int n = static_cast<int>(labels.size());
  if (n < 2 || correlation.rows() != n || correlation.cols() != n) return false;
  size_t longest = 0;
  for (const std::string& label : labels) longest = std::max(longest, label.size());
  const bool values = n <= 12;
  const double cell = values ? 48.0 : std::clamp(720.0 / n, 12.0, 28.0);
  const double char_width = n > 24 ? 6.0 : 7.0;
  const double margin = 24 + char_width * static_cast<double>(std::min<size_t>(longest, 40));
  const double side = cell * n;
  *figure = Figure();
  figure->name = name;
  figure->width = static_cast<int>(std::max(420.0, margin + side + 110));
  figure->height = static_cast<int>(14 + side + margin);
  const PlotFrame frame{figure->width, figure->height};
  std::string cells;
  char line[96];
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (!std::isfinite(correlation(r, c))) continue;
      std::snprintf(line, sizeof(line), "%d %d %.6f\n", c, r, correlation(r, c));
      cells += line;
    }
  }
  if (cells.empty()) return false;
  figure->data.push_back(cells);
  std::ostringstream tics;
  for (int k = 0; k < n; ++k) tics << (k ? ", " : "") << GnuplotString(labels[k]) << " " << k;
  std::ostringstream s;
  s << kPlotStyle << "unset key\nunset grid\n"
    << frame.Area(margin, margin + side, 14, 14 + side) << "set xrange [-0.5:" << n - 0.5
    << "]\nset yrange [" << n - 0.5 << ":-0.5]\n"
    << "set cbrange [-1:1]\nset cbtics 0.5 font ',10'\n"
    << "set palette defined (-1 '#2166ac', -0.5 '#92c5de', 0 '#f7f7f7', 0.5 '#f4a582', "
       "1 '#b2182b')\n"
    << "set colorbox user origin screen " << frame.X(margin + side + 24) << ", screen "
    << frame.Y(14 + side) << " size screen " << 16.0 / figure->width << ", screen "
    << side / figure->height << "\n"
    << "set xtics (" << tics.str() << ") rotate by 90 right nomirror scale 0 font ',"
    << (n > 24 ? 8 : 10) << "'\n"
    << "set ytics (" << tics.str() << ") nomirror scale 0 font '," << (n > 24 ? 8 : 10) << "'\n"
    << "plot D0 using 1:2:(0.5):(0.5):3 with boxxyerror fs solid 1.0 noborder fc palette";
  if (values) {
    s << ", D0 using 1:2:(abs($3) >= 0.6 ? sprintf('%.2f', $3) : '') with labels "
         "tc rgb 'white' font ',10'"
      << ", D0 using 1:2:(abs($3) < 0.6 ? sprintf('%.2f', $3) : '') with labels "
         "tc rgb 'black' font ',10'";
  }
  s << "\n";
  figure->script = s.str();
  return true;
}

bool CostHistoryFigure(const std::string& name, const StageSummary& summary, Figure* figure) {
  *figure = Figure();
  figure->name = name;
  // Refinements: [0] from the start point, global candidates last, extra starts between.
  const size_t count = summary.refinements.size();
  const size_t candidates = summary.global.run ? summary.global.candidates.size() : 0;
  std::vector<std::string> refinements;
  size_t longest = 0;
  for (size_t r = 0; r < count; ++r) {
    const SeriesPiece piece = PositiveHistory(summary.refinements[r].cost_history);
    if (piece.y.size() < 2) continue;
    longest = std::max(longest, summary.refinements[r].cost_history.size());
    figure->data.push_back(SeriesData({piece}, kSignalPoints));
    std::string label = r == 0 ? "from the start point"
                        : r + candidates >= count
                            ? "global candidate " + std::to_string(r + candidates - count + 1)
                            : "extra start " + std::to_string(r);
    const bool chosen = static_cast<int>(r) == summary.chosen;
    if (chosen) label += " (chosen)";
    static const char* kColors[] = {"#1f77b4", "#ff7f0e", "#9467bd",
                                    "#8c564b", "#17becf", "#7f7f7f"};
    const std::string color = chosen ? "#d62728" : kColors[refinements.size() % 6];
    refinements.push_back(
        "D" + std::to_string(figure->data.size() - 1) + " using 1:2 " +
        (chosen ? "with linespoints lw 2.4 pt 7 ps 0.6 " : "with linespoints lw 1.2 pt 6 ps 0.6 ") +
        "lc rgb '" + color + "' title " + GnuplotString(label));
  }
  int global = -1;
  if (summary.global.run) {
    const SeriesPiece piece = PositiveHistory(summary.global.best_cost_history);
    if (piece.y.size() >= 2) {
      SeriesPiece counted = piece;
      for (double& x : counted.x) x += 1.0;  // evaluations count from 1
      figure->data.push_back(SeriesData({counted}, kSignalPoints));
      global = static_cast<int>(figure->data.size()) - 1;
    }
  }
  if (refinements.empty() && global < 0) return false;
  const bool both = !refinements.empty() && global >= 0;
  figure->width = both ? 1100 : 720;
  figure->height = 340;
  std::ostringstream s;
  // Headroom on top keeps the key off the curves, which start high on the left.
  s << kPlotStyle << "set logscale y\nset format y '%.1e'\nset key top right font ',10'\n"
    << "set offsets 0, 0, graph 0.3, 0\n";
  if (both) s << "set multiplot layout 1,2\n";
  if (global >= 0) {
    s << "set title 'global start: best cost so far' font ',11'\n"
      << "set xlabel 'evaluation'\nset ylabel 'cost'\n"
      << "plot D" << global
      << " using 1:2 with steps lw 1.8 lc rgb '#2ca02c' title 'best of the evaluations'\n";
  }
  if (!refinements.empty()) {
    s << "set title 'local refinements: cost per Ceres iteration' font ',11'\n"
      << "set xlabel 'iteration'\nset ylabel 'cost'\n"
      << (longest <= 11 ? "set xtics 1\n" : "set xtics autofreq\n") << "plot ";
    for (size_t k = 0; k < refinements.size(); ++k) s << (k ? ", " : "") << refinements[k];
    s << "\n";
  }
  figure->script = s.str();
  return true;
}

bool TrackFigure(const std::string& name, const std::vector<const ExperimentFit*>& fits,
                 const std::string& north, const std::string& east, Figure* figure) {
  std::vector<SeriesPiece> measured, simulated;
  for (const ExperimentFit* fit : fits) {
    const Trajectory& trace = fit->trace;
    const int n_m = trace.Find(north + "_measured"), e_m = trace.Find(east + "_measured");
    const int n_s = trace.Find(north + "_simulated"), e_s = trace.Find(east + "_simulated");
    if (n_m < 0 || e_m < 0 || n_s < 0 || e_s < 0) continue;
    SeriesPiece m, sim;
    for (size_t k = 0; k < trace.t.size(); ++k) {
      const double nm = trace.columns[n_m][k], em = trace.columns[e_m][k];
      const double ns = trace.columns[n_s][k], es = trace.columns[e_s][k];
      if (std::isfinite(nm) && std::isfinite(em)) {
        m.x.push_back(em);
        m.y.push_back(nm);
      }
      if (std::isfinite(ns) && std::isfinite(es)) {
        sim.x.push_back(es);
        sim.y.push_back(ns);
      }
    }
    if (m.y.empty()) continue;
    measured.push_back(std::move(m));
    if (!sim.y.empty()) simulated.push_back(std::move(sim));
  }
  if (measured.empty()) return false;
  *figure = Figure();
  figure->name = name;
  figure->width = 620;
  figure->height = 560;
  // Decimated along the path (by north, which keeps the turns' extremes in one coordinate).
  figure->data.push_back(SeriesData(measured, 2 * kSignalPoints));
  int sim = -1;
  if (!simulated.empty()) {
    figure->data.push_back(SeriesData(simulated, 2 * kSignalPoints));
    sim = 1;
  }
  std::ostringstream s;
  s << kPlotStyle << "set size ratio -1\nset format x '%g'\nset format y '%g'\n"
    << "set tics font ',10'\nset key top right font ',10' samplen 2\n"
    << "set xlabel " << GnuplotString(WithUnit(east, "m")) << "\nset ylabel "
    << GnuplotString(WithUnit(north, "m")) << "\nset title 'track: north against east' font ',11'\n"
    << PlotList({{0, "with lines lw 3 lc rgb '#8ec1e6' title 'measured'"},
                 {sim, "with lines lw 1.3 lc rgb '#c41e1e' title 'simulated'"}})
    << "\n";
  figure->script = s.str();
  return true;
}

}  // namespace vesselid
