// What `vesselid run` shows while it works. On a terminal: one live status line (stage,
// global or local phase, iteration, cost) rewritten at most ten times a second, and a line per
// finished stage. Not on a terminal (CI logs): the line per finished stage only. Verbose: a
// line per stage start, iteration and note. Quiet: nothing.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "engine/run/pipeline.h"

namespace vesselid {

class TerminalProgress {
 public:
  enum class Mode { kQuiet, kStages, kLive, kVerbose };

  // kLive when `stream` is a terminal, else kStages; quiet and verbose override.
  static Mode ChooseMode(std::FILE* stream, bool quiet, bool verbose);

  TerminalProgress(Mode mode, std::FILE* stream, size_t stages);

  void StageStarted(size_t index, const std::string& name);
  // The run's stage count, once known (`vesselid select`: the chosen candidate's).
  void set_stages(size_t stages) { stages_ = stages; }
  void Iteration(const SolveProgress& progress);
  void StageFinished(const StageResult& stage);
  // A line of its own (resume notes), in every mode but quiet.
  void Note(const std::string& line);

 private:
  void ClearLive();

  Mode mode_;
  std::FILE* stream_;
  size_t stages_;
  size_t index_ = 0;
  std::string stage_;
  bool live_shown_ = false;
  double global_best_ = 0.0;
  std::chrono::steady_clock::time_point stage_start_, last_draw_;
};

}  // namespace vesselid
