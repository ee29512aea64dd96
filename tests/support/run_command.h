// A shell command as a user types it, with its exit status and everything it printed
// (stdout and stderr), for tests of the command line.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace vesselid::testing {

struct CommandOutcome {
  int status;          // the exit status (a signal's death: 128 + signal)
  std::string output;  // stdout and stderr together
};

inline CommandOutcome RunCommand(const std::string& command) {
  CommandOutcome outcome{-1, ""};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return outcome;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) outcome.output += buffer;
  const int status = pclose(pipe);
  outcome.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return outcome;
}

}  // namespace vesselid::testing
