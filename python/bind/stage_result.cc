// vesselid.StageResult: one stage of a run, read-only (run/run_result.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/run/run_result.h"
#include "python/bind/frames.h"
#include "python/bind/types.h"

namespace vesselid::python {
namespace {

// The estimates as a DataFrame indexed by name (model units).
py::object Estimates(const StageResult& stage) {
  py::list name, kind, role, experiment, value, start, std_error, lower, upper, undetermined;
  for (const Estimate& e : stage.estimates) {
    name.append(e.name);
    kind.append(EstimateKindToString(e.kind));
    role.append(ParameterRoleToString(e.role));
    experiment.append(e.experiment);
    value.append(e.value);
    start.append(e.start);
    std_error.append(e.std_error);
    lower.append(e.lower);
    upper.append(e.upper);
    undetermined.append(e.undetermined);
  }
  py::dict columns;
  columns["name"] = name;
  columns["kind"] = kind;
  columns["role"] = role;
  columns["experiment"] = experiment;
  columns["value"] = value;
  columns["start"] = start;
  columns["std_error"] = std_error;
  columns["lower"] = lower;
  columns["upper"] = upper;
  columns["undetermined"] = undetermined;
  return Frame(columns,
               {"name", "kind", "role", "experiment", "value", "start", "std_error", "lower",
                "upper", "undetermined"},
               "name");
}

}  // namespace

void BindStageResult(py::module_& m) {
  py::class_<StageResult>(m, "StageResult",
                          "One stage of a run: its estimates (model units), correlation, cost, "
                          "findings and verdict.")
      .def_readonly("name", &StageResult::name)
      .def_readonly("model", &StageResult::model)
      .def_property_readonly("verdict", [](const StageResult& s) { return VerdictToString(s.verdict); })
      .def_property_readonly("cost", [](const StageResult& s) { return s.summary.local().final_cost; })
      .def_readonly("comparable_cost", &StageResult::comparable_cost)
      .def_property_readonly("iterations",
                             [](const StageResult& s) { return s.summary.local().iterations; })
      .def_property_readonly("time_seconds", [](const StageResult& s) { return s.summary.time_seconds; })
      .def_readonly("integration_step", &StageResult::integration_step)
      .def_readonly("rejected", &StageResult::rejected)
      .def_property_readonly("uncertainty_method",
                             [](const StageResult& s) { return s.summary.uncertainty.method; })
      .def_readonly("findings", &StageResult::findings)
      .def_property_readonly("estimates", &Estimates)
      .def_property_readonly("correlation",
                             [](const StageResult& s) {  // NaN where undetermined
                               return MatrixFrame(s.correlation, s.correlation_names);
                             })
      .def("__repr__", [](const StageResult& s) {
        return "<vesselid.StageResult '" + s.name + "' verdict=" + VerdictToString(s.verdict) + ">";
      });
}

}  // namespace vesselid::python
