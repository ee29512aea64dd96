// How a study part's cases run (study_runner.h): the `study.threads` key as plain data.
#pragma once

namespace vesselid {

struct CaseOptions {
  // Worker threads per process; 0: the machine's cores divided by the processes on it.
  int threads = 0;
};

}  // namespace vesselid
