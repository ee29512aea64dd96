// `vesselid study` as one call, for the command line and Python alike: the config's study
// section on its records, --out checked and locked before the study (under mpirun by rank 0
// once every rank is done: an early return would leave the others waiting in the study's
// collectives), study.txt and study.json published together. Only rank 0 writes. Under
// mpirun the program holds the ProcessGroup (study_runner.h) the command runs in.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "nlohmann/json.hpp"

namespace vesselid {

struct StudyOutcome {
  nlohmann::json result;  // study.json
  std::string text;       // study.txt
  bool root = true;       // this process writes (rank 0)
};

// `write` false: nothing written (out_dir unused); `config_is_file`: the config is an input --out must keep.
bool StudyCommand(const ConfigFile& config, const std::vector<std::string>& only,
                  bool write, const std::string& out_dir, bool config_is_file,
                  const std::function<void(const std::string&)>& progress, StudyOutcome* outcome,
                  std::string* error);

}  // namespace vesselid
