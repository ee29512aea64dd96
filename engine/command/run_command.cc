#include "engine/command/run_command.h"

#include "engine/base/parallel_for.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/checkpoint.h"
#include "engine/output/output_folder.h"
#include "engine/report/results_writer.h"
#include "engine/report/started_gnuplots.h"

namespace vesselid {
namespace {

bool Fail(RunOutcome* outcome, std::string error) {
  outcome->status = RunOutcome::Status::kFailed;
  outcome->error = std::move(error);
  return false;
}

bool StopRequestedBy(const RunRequest& request) {
  return request.stop_requested && request.stop_requested();
}

}  // namespace

bool RunCommand(const RunConfig& config, const RunRequest& request, const RunObserver& observer,
                RunOutcome* outcome) {
  *outcome = RunOutcome();
  const std::string& out_dir = request.out_dir;
  const bool writes = request.write;
  const bool checkpoints = writes && request.checkpoint;
  std::string error, fingerprint;
  std::unique_ptr<OutputFolder> folder;
  std::vector<StageResult> finished;
  if (writes) {
    if ((checkpoints && !RunFingerprint(config, &fingerprint, &error)) ||
        !CheckInputsSurvive(out_dir, RunOutputs(config), RunInputs(config, request.config_is_file),
                            &error)) {
      return Fail(outcome, error);
    }
    folder = OutputFolder::Open(out_dir, &error);
    if (folder == nullptr) return Fail(outcome, error);
    // report.html's gnuplots start now, while the stages run: one per group of figures
    // (RenderFigures draws at most one group per core).
    if (request.html_report) StartGnuplots(ParallelThreads(0));
    if (!AdoptUnpublishedCheckpoint(out_dir, &error)) return Fail(outcome, error);
    if (checkpoints && request.resume && !LoadCheckpoint(out_dir, fingerprint, &finished, &error)) {
      return Fail(outcome, error);
    }
  }
  outcome->resumed = finished.size();
  if (request.resume && request.note) {
    request.note(finished.empty()
                     ? "no checkpoint in " + out_dir + ": starting from the first stage"
                     : "resuming after stage '" + finished.back().name + "' (" +
                           std::to_string(finished.size()) + " of " +
                           std::to_string(config.stages.size()) + " stages from the checkpoint)");
  }
  const size_t stages = config.stages.size();
  size_t interrupted = stages;
  // A checkpoint that cannot be written (a full disk) fails the run like any write: nothing
  // is published, and the earlier set stays whole.
  bool checkpoint_failed = false;
  RunObserver watched = observer;
  watched.stage_finished = [&](size_t index, const StageResult& stage, std::string* message) {
    if (StopRequestedBy(request)) {
      interrupted = index;
      *message = "interrupted";
      return false;
    }
    if (observer.stage_finished && !observer.stage_finished(index, stage, message)) return false;
    if (!checkpoints) return true;
    // A fresh run replaces an earlier checkpoint once its first stage is done.
    if ((index == 0 && !StartCheckpoint(out_dir, fingerprint, message)) ||
        !SaveStageCheckpoint(out_dir, fingerprint, index, stage, message)) {
      checkpoint_failed = true;
      return false;
    }
    return true;
  };
  RunResult& result = outcome->result;
  const bool complete = Identify(config, &result, &error, watched, std::move(finished));
  auto interrupt = [&] {
    // A solve the stop request ended fails its stage, which never reaches stage_finished.
    if (!complete && interrupted == stages) interrupted = result.stages.size();
    outcome->status = RunOutcome::Status::kInterrupted;
    outcome->stage = interrupted;
    return false;
  };
  if (StopRequestedBy(request)) return interrupt();
  if (checkpoint_failed) {
    return Fail(outcome, error + " (the checkpoint could not be written; nothing published: " +
                             out_dir + " is as before)");
  }
  // A run that stopped after finishing a stage still writes what it finished.
  if (!complete && result.stages.empty()) return Fail(outcome, error);
  result.selection = request.selection;
  if (writes) {
    std::string write_error;
    if (!WriteRunResults(config, result, out_dir, &write_error, request.html_report,
                         /*with_checkpoint=*/checkpoints)) {
      if (StopRequestedBy(request)) return interrupt();
      return Fail(outcome, write_error);
    }
    if (checkpoints) RemoveWorkingCheckpoint(out_dir);  // published with the results
  }
  // The model is part of the product, never a reason to fail a run that wrote its results
  // (null where the final values make none: a parameter without a value).
  outcome->model = std::make_shared<IdentifiedModel>();
  std::string model_error;
  if (!IdentifiedModelOf(config, result, 0, 1, outcome->model.get(), &model_error)) {
    outcome->model = nullptr;
  }
  if (!complete) {
    outcome->status = RunOutcome::Status::kStopped;
    outcome->error = error;
    return false;
  }
  outcome->status = RunOutcome::Status::kFinished;
  return true;
}

}  // namespace vesselid
