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
  using E = Estimate;
  return RowsFrame<E>(
      stage.estimates,
      {{"name", [](const E& e) -> py::object { return py::str(e.name); }},
       {"kind", [](const E& e) -> py::object { return py::str(EstimateKindToString(e.kind)); }},
       {"role", [](const E& e) -> py::object { return py::str(ParameterRoleToString(e.role)); }},
       {"experiment", [](const E& e) -> py::object { return py::str(e.experiment); }},
       {"value", [](const E& e) -> py::object { return py::float_(e.value); }},
       {"start", [](const E& e) -> py::object { return py::float_(e.start); }},
       {"std_error", [](const E& e) -> py::object { return py::float_(e.std_error); }},
       {"lower", [](const E& e) -> py::object { return py::float_(e.lower); }},
       {"upper", [](const E& e) -> py::object { return py::float_(e.upper); }},
       {"undetermined", [](const E& e) -> py::object { return py::bool_(e.undetermined); }}},
      "name");
}

// auto's candidates, output error first: name, solved, why, -log L, unknowns, BIC, chosen.
py::object Candidates(const DisturbanceReport& d) {
  using C = DisturbanceCandidateScore;
  return RowsFrame<C>(
      d.candidates,
      {{"name", [](const C& c) -> py::object { return py::str(c.name); }},
       {"solved", [](const C& c) -> py::object { return py::bool_(c.solved); }},
       {"why", [](const C& c) -> py::object { return py::str(c.why); }},
       {"negative_log_likelihood",
        [](const C& c) -> py::object { return py::float_(c.negative_log_likelihood); }},
       {"unknowns", [](const C& c) -> py::object { return py::int_(c.unknowns); }},
       {"bic", [](const C& c) -> py::object { return py::float_(c.bic); }},
       {"chosen", [](const C& c) -> py::object { return py::bool_(c.chosen); }}},
      "name");
}

// The held-out experiments predicted through the filter: a row per experiment and output.
py::object Predictions(const DisturbanceReport& d) {
  using P = FilterPrediction;
  return RowsFrame<P>(
      d.predictions,
      {{"experiment", [](const P& p) -> py::object { return py::str(p.experiment); }},
       {"output", [](const P& p) -> py::object { return py::str(p.output); }},
       {"steps", [](const P& p) -> py::object { return py::int_(p.steps); }},
       {"seconds_ahead", [](const P& p) -> py::object { return py::float_(p.seconds_ahead); }},
       {"k_step_fit_percent",
        [](const P& p) -> py::object { return py::float_(p.k_step_fit_percent); }},
       {"one_step_fit_percent",
        [](const P& p) -> py::object { return py::float_(p.one_step_fit_percent); }},
       {"free_run_fit_percent",
        [](const P& p) -> py::object { return py::float_(p.free_run_fit_percent); }}});
}

}  // namespace

void BindStageResult(py::module_& m) {
  py::class_<DisturbanceReport>(
      m, "Disturbance",
      "A filter-error stage's disturbance model (docs/models.md, \"Disturbance models\"); its "
      "parameters are the stage's estimates of kind 'noise'.\n\n"
      "method       'filter_error' or 'auto'\n"
      "model        the disturbance in words, as the disturbance_model finding names it\n"
      "negative_log_likelihood   the innovations' -log L at the estimates\n"
      "candidates   DataFrame of auto's candidates by name (output error first): solved, why, "
      "negative_log_likelihood, unknowns, bic, chosen; empty for filter_error and where auto "
      "found output error's residuals white (nothing compared)\n"
      "predictions  DataFrame, a row per held-out experiment and output: the k-step and "
      "one-step predictions through the filter and the free run from the measured start (fit %)")
      .def_readonly("method", &DisturbanceReport::method)
      .def_readonly("model", &DisturbanceReport::model)
      .def_readonly("negative_log_likelihood", &DisturbanceReport::negative_log_likelihood)
      .def_property_readonly("candidates", &Candidates)
      .def_property_readonly("predictions", &Predictions)
      .def("__repr__", [](const DisturbanceReport& d) {
        return "<vesselid.Disturbance " + d.method + ": " + d.model + ">";
      });

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
      .def_property_readonly(
          "disturbance",
          [](const StageResult& s) -> const DisturbanceReport* {
            return s.disturbance.active() ? &s.disturbance : nullptr;  // None: output error
          },
          py::return_value_policy::reference_internal)
      .def_property_readonly("correlation",
                             [](const StageResult& s) {  // NaN where undetermined
                               return MatrixFrame(s.correlation, s.correlation_names);
                             })
      .def("__repr__", [](const StageResult& s) {
        return "<vesselid.StageResult '" + s.name + "' verdict=" + VerdictToString(s.verdict) + ">";
      });
}

}  // namespace vesselid::python
