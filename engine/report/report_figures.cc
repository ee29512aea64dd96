#include "engine/report/report_figures.h"

#include <stdlib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "engine/base/parallel_for.h"
#include "engine/base/text_match.h"
#include "engine/report/decimation.h"
#include "engine/report/started_gnuplots.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;

// Figures after a failing one are retried at most this often.
constexpr int kMaxRuns = 6;
// gnuplot's messages kept per failed run.
constexpr size_t kMaxMessage = 1500;

std::string ShellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

bool WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return static_cast<bool>(out);
}

std::string DataName(size_t figure, size_t k) {
  return "f" + std::to_string(figure) + "_" + std::to_string(k) + ".dat";
}

std::string SvgName(size_t figure) { return "f" + std::to_string(figure) + ".svg"; }

// The script drawing figures [first, end); each finished figure prints its index to `done`.
std::string Script(const std::vector<Figure>& figures, size_t first, size_t end,
                   const std::string& folder, const std::string& done) {
  std::ostringstream s;
  s << "cd " << GnuplotString(folder) << "\n"
    << "set print " << GnuplotString(done) << "\n";
  for (size_t i = first; i < end; ++i) {
    const Figure& f = figures[i];
    s << "reset\n"
      << "set encoding utf8\n"
      << "set terminal svg size " << f.width << "," << f.height
      << " font 'DejaVu Sans,11' noenhanced background rgb 'white'\n"
      << "set output " << GnuplotString(SvgName(i)) << "\n"
      << "set datafile missing 'NaN'\n";
    for (size_t k = 0; k < f.data.size(); ++k) {
      s << "D" << k << " = " << GnuplotString(DataName(i, k)) << "\n";
    }
    s << f.script << "\nunset multiplot\nset output\nprint " << i << "\n";
  }
  return s.str();
}

std::string Tail(const std::string& text) {
  return text.size() <= kMaxMessage ? text : "..." + text.substr(text.size() - kMaxMessage);
}

// Bounds of `groups` contiguous runs of figures of about equal work: a figure weighs its data
// bytes plus a fixed share for gnuplot's own drawing.
std::vector<size_t> GroupBounds(const std::vector<Figure>& figures, size_t groups) {
  constexpr size_t kFigureBytes = 20000;
  std::vector<size_t> weight;
  size_t total = 0;
  for (const Figure& f : figures) {
    size_t w = kFigureBytes;
    for (const std::string& d : f.data) w += d.size();
    weight.push_back(w);
    total += w;
  }
  std::vector<size_t> bounds{0};
  size_t sum = 0;
  for (size_t i = 0; i < figures.size(); ++i) {
    sum += weight[i];
    const size_t g = bounds.size();  // the group being filled
    if (g < groups && i + 1 < figures.size() && sum * groups >= total * g) bounds.push_back(i + 1);
  }
  bounds.push_back(figures.size());
  return bounds;
}

// Draws figures [begin, end) with gnuplot into result->svg; gnuplot's messages into *error.
void DrawGroup(const std::vector<Figure>& figures, size_t begin, size_t end,
               const fs::path& folder, const std::string& group, FigureRendering* result,
               std::string* error) {
  size_t first = begin;
  for (int run = 0; run < kMaxRuns && first < end; ++run) {
    const std::string tag = group + "_" + std::to_string(run);
    const fs::path script = folder / ("figures" + tag + ".gp");
    const fs::path messages = folder / ("gnuplot" + tag + ".txt");
    if (!WriteFile(script, Script(figures, first, end, folder.string(), "done" + tag + ".txt"))) {
      *error = script.string() + ": write failed: " + std::strerror(errno);
      break;
    }
    // The first run takes a gnuplot started ahead (started_gnuplots.h) if there is one.
    int status = 0;
    std::string started_messages;
    if (run == 0 && RunStartedGnuplot(script.string(), &status, &started_messages)) {
      WriteFile(messages, started_messages);
    } else {
      const std::string command = "gnuplot -d " + ShellQuote(script.string()) +
                                  " > /dev/null 2> " + ShellQuote(messages.string());
      status = std::system(command.c_str());
    }
    std::set<size_t> done;
    std::istringstream done_list(ReadFile(folder / ("done" + tag + ".txt")));
    for (size_t i; done_list >> i;) done.insert(i);
    for (size_t i : done) result->svg[i] = ReadFile(folder / SvgName(i));
    if (status == 0) break;
    const bool missing = status == -1 || (WIFEXITED(status) && WEXITSTATUS(status) == 127);
    size_t failed = first;
    while (failed < end && done.count(failed) > 0) ++failed;
    if (!error->empty()) *error += "\n";
    if (missing) {
      *error += "gnuplot could not be run: " + Tail(ReadFile(messages));
      break;
    }
    *error += (failed < end ? "figure " + figures[failed].name + ": " : "") +
              Tail(ReadFile(messages));
    first = failed + 1;
  }
}

}  // namespace

std::string GnuplotString(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out + "'";
}

std::string GnuplotNumber(double value) {
  if (!std::isfinite(value)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof(text), "%.7g", value);
  return text;
}

std::string SeriesData(const std::vector<SeriesPiece>& pieces, size_t max_points) {
  size_t total = 0;
  for (const SeriesPiece& p : pieces) total += p.y.size();
  std::string out;
  char line[64];
  bool first = true;
  for (const SeriesPiece& p : pieces) {
    if (p.y.empty()) continue;
    const size_t share =
        total <= max_points ? p.y.size() : std::max<size_t>(2, max_points * p.y.size() / total);
    if (!first) out += "\n";
    first = false;
    for (size_t k : MinMaxDecimation(p.y, share)) {
      std::snprintf(line, sizeof(line), "%.9g %.7g\n", p.x[k], p.y[k]);
      out += line;
    }
  }
  return out;
}

// The plots' temporary folders, "vesselid_report_<pid>_XXXXXX" in the temporary directory,
// of processes no longer alive (killed while drawing): removed before a new one is made.
constexpr char kFolderPrefix[] = "vesselid_report_";

static void RemoveStaleFigureFolders() {
  const std::string prefix = kFolderPrefix;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(fs::temp_directory_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (!StartsWith(name, prefix) || !entry.is_directory(ec) || entry.is_symlink(ec)) continue;
    const size_t end = name.find('_', prefix.size());
    if (end == std::string::npos || end == prefix.size()) continue;
    const std::string digits = name.substr(prefix.size(), end - prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid <= 0 || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours
    std::error_code ignored;
    fs::remove_all(entry.path(), ignored);
  }
}

FigureRendering RenderFigures(const std::vector<Figure>& figures) {
  FigureRendering result;
  result.svg.assign(figures.size(), "");
  if (figures.empty()) return result;
  RemoveStaleFigureFolders();
  std::string pattern = (fs::temp_directory_path() /
                         (kFolderPrefix + std::to_string(::getpid()) + "_XXXXXX"))
                            .string();
  if (mkdtemp(pattern.data()) == nullptr) {
    result.error =
        "cannot create a temporary folder for the plots in " + fs::temp_directory_path().string();
    return result;
  }
  const fs::path folder = pattern;
  for (size_t i = 0; i < figures.size(); ++i) {
    for (size_t k = 0; k < figures[i].data.size(); ++k) {
      if (!WriteFile(folder / DataName(i, k), figures[i].data[k])) {
        result.error = (folder / DataName(i, k)).string() + ": write failed: " + std::strerror(errno);
        fs::remove_all(folder);
        return result;
      }
    }
  }
  const std::vector<size_t> bounds = GroupBounds(
      figures, std::min(figures.size(), static_cast<size_t>(ParallelThreads(0))));
  const int groups = static_cast<int>(bounds.size()) - 1;
  std::vector<std::string> errors(groups);
  ParallelFor(groups, 0, [&](int g) {
    DrawGroup(figures, bounds[g], bounds[g + 1], folder, std::to_string(g), &result, &errors[g]);
  });
  for (const std::string& e : errors) {
    if (e.empty()) continue;
    // gnuplot missing is one message, not one per group.
    if (result.error.find(e) != std::string::npos) continue;
    result.error += (result.error.empty() ? "" : "\n") + e;
  }
  std::error_code ec;
  fs::remove_all(folder, ec);
  return result;
}

}  // namespace vesselid
