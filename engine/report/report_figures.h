// Figures of the HTML report, drawn by gnuplot to SVG. A figure is its data (whitespace-
// separated text files) and the gnuplot commands that draw it. RenderFigures writes the data of
// every figure into a private temporary folder, splits the figures into contiguous groups of
// about equal data size, one per core, and runs one gnuplot per group in parallel on a script
// for its figures (`gnuplot` from PATH; Debian package gnuplot-nox); then it reads the SVGs back
// and removes the folder. Every figure's script starts with `reset`, so a figure draws the same
// in any group. gnuplot stops at its first error, so after a failing figure it is run again
// on the figures of its group that follow, a few times at most.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vesselid {

struct Figure {
  std::string name;               // short key, unique within a report
  int width = 900, height = 400;  // pixels
  std::vector<std::string> data;  // file contents; the script names them D0, D1, ...
  std::string script;             // gnuplot commands drawing the figure; the terminal (SVG,
                                  // noenhanced, UTF-8), the output and the variables D<k>
                                  // are set before them, `set datafile missing 'NaN'` too
};

struct FigureRendering {
  std::vector<std::string> svg;  // per figure; empty when it was not drawn
  std::string error;             // why some or all were not drawn (gnuplot's messages)
};

FigureRendering RenderFigures(const std::vector<Figure>& figures);

// `text` as a gnuplot single-quoted string literal: quotes doubled, control characters as
// spaces. With the terminal's noenhanced option it prints literally (underscores included).
std::string GnuplotString(const std::string& text);

// A number for a gnuplot script or data file ("NaN" when not finite).
std::string GnuplotNumber(double value);

// The common look of the report's figures (border, grid, tic and key colours).
inline constexpr char kPlotStyle[] =
    "set border lw 1 lc rgb '#606060'\n"
    "set grid lt 1 lw 1 lc rgb '#e4e4e4'\n"
    "set tics textcolor rgb '#303030'\n"
    "set key textcolor rgb '#303030'\n";

// Pixel positions in a figure of width x height pixels (y from the top) as gnuplot screen
// coordinates, and the margins that put the next plot's area at given pixels.
struct PlotFrame {
  int width, height;
  double X(double px) const { return px / width; }
  double Y(double px) const { return 1.0 - px / height; }
  std::string Area(double left, double right, double top, double bottom) const {
    return "set lmargin at screen " + std::to_string(X(left)) + "\nset rmargin at screen " +
           std::to_string(X(right)) + "\nset tmargin at screen " + std::to_string(Y(top)) +
           "\nset bmargin at screen " + std::to_string(Y(bottom)) + "\n";
  }
};

// Points of a series; a series of several pieces (one per segment of a record) is drawn as
// separate lines.
struct SeriesPiece {
  std::vector<double> x, y;
};

// A data file of "x y" lines, pieces separated by a blank line, each piece min/max-decimated
// (decimation.h) to its share of `max_points` by length. Pieces hold finite values only.
std::string SeriesData(const std::vector<SeriesPiece>& pieces, size_t max_points);

}  // namespace vesselid
