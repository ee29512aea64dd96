#include "engine/command/select_command.h"

#include "engine/select/selection.h"
#include "engine/study/study_runner.h"

namespace vesselid {

bool SelectCommand(const SelectionSetup& setup, const RunRequest& request,
                   const RunObserver& observer,
                   const std::function<void(const std::string&)>& progress,
                   const std::function<void(const SelectOutcome&)>& selected,
                   SelectOutcome* outcome, std::string* error) {
  const ProcessGroup& group = ProcessGroup::Current();
  outcome->root = group.root();
  outcome->selection = std::make_shared<SelectionResult>();
  if (!RunSelection(setup.candidates, setup.options, outcome->selection.get(), error, progress)) {
    return false;
  }
  if (!group.root()) return true;
  if (outcome->selection->chosen < 0) {
    *error = "select: " + outcome->selection->reason;
    return false;
  }
  outcome->chosen = &setup.candidates[outcome->selection->chosen].config;
  if (selected) selected(*outcome);
  RunRequest chosen = request;
  chosen.selection = outcome->selection;
  RunCommand(*outcome->chosen, chosen, observer, &outcome->run);
  return true;
}

}  // namespace vesselid
