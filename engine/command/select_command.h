// `vesselid select` as one call, for the command line and Python alike: every candidate of
// the config's select section cross-validated over its runs (a case per candidate and fold,
// over threads and MPI ranks), then the chosen one run as `vesselid run` runs a config
// (run_command.h), its outputs showing the selection. Only rank 0 runs the chosen candidate.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/command/run_command.h"
#include "engine/select/selection_config.h"

namespace vesselid {

struct SelectOutcome {
  std::shared_ptr<SelectionResult> selection;
  const RunConfig* chosen = nullptr;  // the chosen candidate's config (in the setup)
  RunOutcome run;
  bool root = true;  // this process ran the chosen candidate (rank 0)
};

// `progress`: a line per finished case; `selected` (may be null): the selection, before the
// chosen candidate runs. False with `error` when the selection failed or chose
// nothing; true once the chosen candidate ran, however its run ended (outcome->run).
bool SelectCommand(const SelectionSetup& setup, const RunRequest& request,
                   const RunObserver& observer,
                   const std::function<void(const std::string&)>& progress,
                   const std::function<void(const SelectOutcome&)>& selected,
                   SelectOutcome* outcome, std::string* error);

}  // namespace vesselid
