#include "engine/command/study_command.h"

#include <filesystem>
#include <memory>

#include "engine/base/atomic_file.h"
#include "engine/output/output_folder.h"
#include "engine/output/output_staging.h"
#include "engine/study/study_json.h"
#include "engine/study/study_runner.h"

namespace vesselid {

bool StudyCommand(const ConfigFile& config, const std::vector<std::string>& only,
                  bool write, const std::string& out_dir, bool config_is_file,
                  const std::function<void(const std::string&)>& progress, StudyOutcome* outcome,
                  std::string* error) {
  const ProcessGroup& group = ProcessGroup::Current();
  outcome->root = group.root();
  std::unique_ptr<OutputFolder> folder;
  auto open_output = [&] {
    if (!write) return true;
    if (!CheckInputsSurvive(out_dir, RunOutputs(config.run),
                            RunInputs(config.run, config_is_file), error)) {
      return false;
    }
    folder = OutputFolder::Open(out_dir, error);
    return folder != nullptr;
  };
  if (group.size() == 1 && !open_output()) return false;
  if (!RunStudy(config.run, config.study, only, &outcome->result, &outcome->text, error,
                progress)) {
    return false;
  }
  if (!group.root() || !write) return true;
  if (folder == nullptr && !open_output()) return false;
  // study.txt and study.json appear together (output_staging.h).
  const auto staging = OutputStaging::Begin(out_dir, "study", error);
  if (staging == nullptr) return false;
  const std::filesystem::path out(staging->folder());
  return WriteFileAtomically((out / "study.txt").string(), outcome->text, error) &&
         WriteFileAtomically((out / "study.json").string(), outcome->result.dump(2) + "\n",
                             error) &&
         staging->Publish("study.json", error);
}

}  // namespace vesselid
