#include "engine/cli/terminal_progress.h"

#include <unistd.h>

namespace vesselid {
namespace {

constexpr double kRedrawSeconds = 0.1;

double Since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TerminalProgress::Mode TerminalProgress::ChooseMode(std::FILE* stream, bool quiet, bool verbose) {
  if (quiet) return Mode::kQuiet;
  if (verbose) return Mode::kVerbose;
  return isatty(fileno(stream)) ? Mode::kLive : Mode::kStages;
}

TerminalProgress::TerminalProgress(Mode mode, std::FILE* stream, size_t stages)
    : mode_(mode), stream_(stream), stages_(stages) {}

void TerminalProgress::ClearLive() {
  if (!live_shown_) return;
  std::fputs("\r\033[K", stream_);
  live_shown_ = false;
}

void TerminalProgress::StageStarted(size_t index, const std::string& name) {
  index_ = index;
  stage_ = name;
  stage_start_ = last_draw_ = std::chrono::steady_clock::now();
  if (mode_ == Mode::kVerbose) {
    std::fprintf(stream_, "[%zu/%zu] stage %s: running\n", index + 1, stages_, name.c_str());
  } else if (mode_ == Mode::kLive) {
    ClearLive();
    std::fprintf(stream_, "[%zu/%zu] stage %s: preparing", index + 1, stages_, name.c_str());
    live_shown_ = true;
  }
  std::fflush(stream_);
}

void TerminalProgress::Iteration(const SolveProgress& p) {
  if (mode_ != Mode::kLive && mode_ != Mode::kVerbose) return;
  if (mode_ == Mode::kLive && Since(last_draw_) < kRedrawSeconds) return;
  // Verbose global search: a line when the best cost improves and every 100 evaluations.
  if (mode_ == Mode::kVerbose && p.phase == SolveProgress::Phase::kGlobal) {
    const bool improved = p.iteration == 1 || p.cost < global_best_;
    global_best_ = p.cost;
    if (!improved && p.iteration % 100 != 0) return;
  }
  last_draw_ = std::chrono::steady_clock::now();
  char phase[128];
  int n = 0;
  if (p.segment_length > 0.0) {
    n = std::snprintf(phase, sizeof(phase), "continuation on %g s segments, ", p.segment_length);
  }
  if (p.phase == SolveProgress::Phase::kGlobal) {
    std::snprintf(phase + n, sizeof(phase) - n, "global search, evaluation %d, best cost",
                  p.iteration);
  } else {
    std::snprintf(phase + n, sizeof(phase) - n, "local refinement %d/%d, iteration %d, cost",
                  p.refinement + 1, p.refinements, p.iteration);
  }
  if (mode_ == Mode::kLive) ClearLive();
  std::fprintf(stream_, "[%zu/%zu] stage %s: %s %.6e (%.1f s)%s", index_ + 1, stages_,
               stage_.c_str(), phase, p.cost, Since(stage_start_),
               mode_ == Mode::kVerbose ? "\n" : "");
  live_shown_ = mode_ == Mode::kLive;
  std::fflush(stream_);
}

void TerminalProgress::StageFinished(const StageResult& stage) {
  if (mode_ == Mode::kQuiet) return;
  ClearLive();
  std::fprintf(stream_, "[%zu/%zu] %s\n", index_ + 1, stages_,
               stage.summary.BriefReport().c_str());
  if (mode_ == Mode::kVerbose) {
    for (const std::string& note : stage.summary.notes) {
      std::fprintf(stream_, "        note: %s\n", note.c_str());
    }
  }
  std::fflush(stream_);
}

void TerminalProgress::Note(const std::string& line) {
  if (mode_ == Mode::kQuiet) return;
  ClearLive();
  std::fprintf(stream_, "%s\n", line.c_str());
  std::fflush(stream_);
}

}  // namespace vesselid
