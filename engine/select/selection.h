// Model-structure selection by cross-validation over whole runs (`vesselid select`).
//
// Each candidate is a complete run config (its model, stages, held parameters; built from the
// config's `select:` section, selection_config.h). The runs are split into folds by run:
// leave-one-run-out, or k folds (run i in fold i mod k, in the listed order). For every
// candidate and fold the candidate's stages are fitted on the runs the fold keeps (every
// stage's experiments less the fold's runs; stage validation off) and the fold's runs are
// predicted with the final values, each held-out run estimating its own per-run parameters
// (a rudder bias) and free initial states with the shared ones held (final validation,
// per_experiment: fit). A fold's score is the mean free-run fit % over its runs and the
// scored outputs; a candidate's is the mean over folds with its standard error (SD / sqrt of
// the folds). A last case per candidate fits every run: its estimated numbers and the
// information criteria of its scored residuals (selection_result.h). The choice is the
// one-standard-error rule's (selection_choice.h).
//
// Every (candidate, fold) is a case of study_runner.h (threads and MPI ranks), merged on rank
// 0 in index order: the result is the same for any number of threads or ranks.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/selection_result.h"
#include "engine/study/case_options.h"

namespace vesselid {

struct NamedCandidate {
  std::string name;
  RunConfig config;
};

struct SelectionOptions {
  std::vector<std::string> runs;  // the runs cross-validated, in order
  int folds = 0;                  // 0: leave one run out; k >= 2: k folds by run
  // The scored outputs; empty: those every candidate's experiments map.
  std::vector<std::string> outputs;
  CaseOptions cases;
};

// The folds of `runs`: each the runs it holds out.
std::vector<std::vector<std::string>> FoldsByRun(const std::vector<std::string>& runs, int folds);

// On rank 0 `result` holds the scores and the choice; false with a message when the options
// do not fit the candidates (a run or scored output a candidate lacks). `progress` gets one
// line per finished case.
bool RunSelection(const std::vector<NamedCandidate>& candidates, const SelectionOptions& options,
                  SelectionResult* result, std::string* error,
                  const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace vesselid
