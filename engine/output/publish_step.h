// A test's kill point inside a publication (tests/system/hostile_input_test.cc,
// command_limits_test.cc): with VESSELID_TEST_KILL_AT_PUBLISH_STEP set to k, the process sends
// itself SIGKILL once k of the publication's steps (each removal, move, exchange and manifest
// write) are taken: a kill -9 at exactly that point. Unset in use.
#pragma once

namespace vesselid {

void PublishStepTaken();

}  // namespace vesselid
