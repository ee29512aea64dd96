#include "engine/report/started_gnuplots.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <vector>

#include "engine/report/report_figures.h"

extern char** environ;

namespace vesselid {
namespace {

struct StartedGnuplot {
  pid_t pid = -1;
  int input = -1;               // write end of its standard input
  std::FILE* errors = nullptr;  // an unnamed file holding its standard error
};

// The processes started and not yet handed a script. At exit the unused ones get the end of
// their input (and exit, not waited for: they may still be starting).
class StartedGnuplots {
 public:
  ~StartedGnuplots() {
    for (StartedGnuplot& g : idle_) {
      ::close(g.input);
      std::fclose(g.errors);
    }
  }

  void Start(int count) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (int i = 0; i < count; ++i) {
      StartedGnuplot g;
      if (!Spawn(&g)) break;
      idle_.push_back(g);
    }
  }

  bool Take(StartedGnuplot* g) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (idle_.empty()) return false;
    *g = idle_.back();
    idle_.pop_back();
    return true;
  }

  // Closes its input and waits for it; its wait status.
  static int Finish(StartedGnuplot* g) {
    if (g->input >= 0) ::close(g->input);
    g->input = -1;
    int status = 0;
    while (::waitpid(g->pid, &status, 0) < 0 && errno == EINTR) {
    }
    return status;
  }

 private:
  static bool Spawn(StartedGnuplot* g) {
    int pipe[2];
    if (::pipe2(pipe, O_CLOEXEC) != 0) return false;
    g->errors = std::tmpfile();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe[0], 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    if (g->errors != nullptr) posix_spawn_file_actions_adddup2(&actions, fileno(g->errors), 2);
    char name[] = "gnuplot", option[] = "-d";
    char* argv[] = {name, option, nullptr};
    const int failed =
        g->errors == nullptr ? -1 : posix_spawnp(&g->pid, name, &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipe[0]);
    if (failed != 0) {
      ::close(pipe[1]);
      if (g->errors != nullptr) std::fclose(g->errors);
      return false;
    }
    g->input = pipe[1];
    return true;
  }

  std::mutex mutex_;
  std::vector<StartedGnuplot> idle_;
};

StartedGnuplots& Processes() {
  static StartedGnuplots processes;
  return processes;
}

// Writes `text` to a pipe whose reader may have exited: SIGPIPE is blocked for this thread
// and a pending one taken back, so a gnuplot that died does not end the run.
bool WriteToPipe(int fd, const std::string& text) {
  sigset_t pipe_signal, old;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &old);
  size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<size_t>(n);
  }
  if (written < text.size()) {
    const timespec now{0, 0};
    while (sigtimedwait(&pipe_signal, nullptr, &now) < 0 && errno == EINTR) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return written == text.size();
}

std::string ReadAll(std::FILE* file) {
  std::string text;
  struct stat info;
  if (file == nullptr || ::fstat(fileno(file), &info) != 0) return text;
  text.resize(static_cast<size_t>(info.st_size));
  const ssize_t n = ::pread(fileno(file), text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<size_t>(n) : 0);
  return text;
}

}  // namespace

void StartGnuplots(int count) { Processes().Start(count); }

bool RunStartedGnuplot(const std::string& script, int* status, std::string* messages) {
  StartedGnuplot g;
  if (!Processes().Take(&g)) return false;
  // One that died before reading its script has drawn nothing: the caller starts its own.
  const bool sent = WriteToPipe(g.input, "load " + GnuplotString(script) + "\n");
  *status = StartedGnuplots::Finish(&g);
  *messages = ReadAll(g.errors);
  std::fclose(g.errors);
  return sent;
}

}  // namespace vesselid
