// `vesselid run` as one call, for the command line and Python alike: the output folder checked
// and locked before anything runs (nothing written replaces an input), a checkpoint after
// each stage, a resume from it, a stop request honoured between stages, and the outputs
// published as one set (report/results_writer.h). The caller shows progress (the observer)
// and says what happened (RunOutcome).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/output/identified_model.h"
#include "engine/run/pipeline.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

struct RunRequest {
  bool write = true;            // false: no outputs (a notebook's run), out_dir unused
  std::string out_dir;          // checked: an empty one is refused
  bool config_is_file = true;   // the config is an input --out must not replace
  // A checkpoint after each stage, published with the results (needs the config and records
  // as files: it is keyed by their contents); Python's runs take theirs from memory.
  bool checkpoint = true;
  bool resume = false;          // go on from the checkpoint in out_dir
  bool html_report = true;      // report.html beside results.json and report.txt
  // The structure selection that chose the config (`vesselid select`), shown in every output.
  std::shared_ptr<const SelectionResult> selection;
  // Asked after each stage (and by the solves through stop_request.h): true stops the run
  // there, and nothing is published.
  std::function<bool()> stop_requested;
  // A line for the user before the stages run (what a resume takes from the checkpoint).
  std::function<void(const std::string&)> note;
};

struct RunOutcome {
  enum class Status {
    kFinished,     // every stage ran; the outputs are published
    kStopped,      // a stage failed after others finished: those are published
    kFailed,       // nothing ran or nothing could be written: `error`
    kInterrupted,  // stop_requested: nothing published; `stage` where it stopped
  };
  Status status = Status::kFailed;
  RunResult result;
  // kFinished and kStopped: the identified model of the final values (no ensemble; what the
  // run's results.json gives, output/identified_model.h); null where they make none.
  std::shared_ptr<IdentifiedModel> model;
  std::string error;
  // kInterrupted: the stage cut short (config.stages.size(): after the last one, before
  // publication).
  size_t stage = 0;
  size_t resumed = 0;  // stages taken from the checkpoint
};

// Runs `config` as the request says; `observer` sees the stages and iterations (its
// stage_finished, if any, is asked before the checkpoint is saved). False when the run did
// not finish (outcome->status says how).
bool RunCommand(const RunConfig& config, const RunRequest& request, const RunObserver& observer,
                RunOutcome* outcome);

}  // namespace vesselid
