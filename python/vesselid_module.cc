// vesselid._core: the engine's types and commands for the Python package (python/vesselid/).
// One binder per public concept (python/bind/): Finding, StageResult, RunResult,
// IdentifiedModel; the commands are the ones the `vesselid` program calls (engine/command/).
#include <pybind11/pybind11.h>

#include "engine/base/version.h"
#include "python/bind/errors.h"
#include "python/bind/types.h"

PYBIND11_MODULE(_core, m) {
  namespace python = vesselid::python;
  m.doc() = "vesselid engine types and commands (use the vesselid package)";
  m.attr("__version__") = vesselid::kVersion;
  python::RegisterErrors();
  python::BindFinding(m);
  python::BindStageResult(m);
  python::BindRunResult(m);
  python::BindIdentifiedModel(m);
  python::BindCommands(m);
}
