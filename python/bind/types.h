// The classes the package binds, one binder per public concept (as manif and Crocoddyl bind
// theirs): Finding, StageResult, RunResult, IdentifiedModel; read-only views of the engine's
// own types. A RunResult holds its run (config and result); what it hands out (stages, the
// model) keeps it alive.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "engine/output/identified_model.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid::python {

namespace py = pybind11;

// A finished run as Python holds it.
struct Run {
  std::shared_ptr<const RunConfig> config;
  RunResult result;
  std::string json;     // results.json's text, unindented (RunResult.to_json())
  std::string summary;  // report.txt's text
  std::shared_ptr<IdentifiedModel> model;  // the run's (RunOutcome::model)
};

void BindFinding(py::module_& m);
void BindStageResult(py::module_& m);
void BindRunResult(py::module_& m);
void BindIdentifiedModel(py::module_& m);
void BindCommands(py::module_& m);

}  // namespace vesselid::python
