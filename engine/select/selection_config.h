// The `select:` section of a config (`vesselid select`): the candidate structures and how they
// are cross-validated.
//
//   select:
//     experiments: training          # the runs cross-validated: a set, or a list (default:
//                                    # the first stage's experiments)
//     folds: leave_one_run_out       # | k >= 2: k folds by run (run i in fold i mod k)
//     outputs: [psi]                 # scored outputs (default: those every candidate maps)
//     threads: 0                     # cases in parallel (0: the machine's cores)
//     candidates:
//       - {name: mmg}                # the config as it is
//       - name: norrbin_n1           # the config with these top-level keys replaced
//         model: {family: nomoto, type: norrbin_n1, length: 7}
//         experiment_defaults: {inputs: {delta: delta, U: U}, outputs: {psi: psi}}
//         stages: [...]
//         final_validation: {...}
//
// A candidate may replace model, experiment_defaults, experiments, sets, stages, fusion,
// final and final_validation; each is built and checked as a config of its own (an error
// names the candidate and the key).
#pragma once

#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/config/model_registry.h"
#include "engine/select/selection.h"

namespace vesselid {

struct SelectionSetup {
  SelectionOptions options;
  std::vector<NamedCandidate> candidates;
};

// Experiment files resolve against data_dir when it is not empty, else against the config
// file's folder. False with a message naming file, line and key.
bool LoadSelection(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, SelectionSetup* setup, std::string* error);

// The same from a config's text (source.text, named by source.path) and records given in
// memory (source.in_memory: experiments whose tables the caller attaches to every candidate).
bool LoadSelection(const ConfigSource& source, const ModelRegistry& registry,
                   SelectionSetup* setup, std::string* error);

}  // namespace vesselid
