// gnuplot processes started ahead of the report. A gnuplot takes about 0.1 s to start (loading
// its libraries and fonts) before it draws anything; a run that will write report.html starts
// them while its stages run, and RenderFigures (report_figures.h) hands each one a script.
// A started gnuplot waits on its standard input (a pipe) for one `load '<script>'` line, runs
// that script and exits at the end of its input, as `gnuplot -d <script>` does: it stops at the
// script's first error with a non-zero status, its messages kept. Processes never handed a
// script see the end of their input when the run ends and exit.
#pragma once

#include <string>

namespace vesselid {

// Starts up to `count` gnuplot processes (from PATH) for this process's report; fewer, or
// none, when gnuplot cannot be started (RenderFigures then starts its own and reports why).
void StartGnuplots(int count);

// Runs `script` in one started gnuplot, if one is left: true, with its wait status (as
// std::system returns it) and what it wrote to its standard error; false when none is left
// or the one taken had exited before it could be given the script.
bool RunStartedGnuplot(const std::string& script, int* status, std::string* messages);

}  // namespace vesselid
