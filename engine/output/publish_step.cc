#include "engine/output/publish_step.h"

#include <csignal>
#include <cstdlib>

namespace vesselid {

void PublishStepTaken() {
  static const int kill_at = [] {
    const char* text = std::getenv("VESSELID_TEST_KILL_AT_PUBLISH_STEP");
    return text != nullptr ? std::atoi(text) : 0;
  }();
  static int taken = 0;
  if (kill_at > 0 && ++taken == kill_at) ::raise(SIGKILL);
}

}  // namespace vesselid
