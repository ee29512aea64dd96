// vesselid.Finding: one typed finding of a run (`vesselid findings` lists the kinds).
#include <pybind11/pybind11.h>

#include <cmath>

#include "engine/base/finding.h"
#include "python/bind/types.h"

namespace vesselid::python {

void BindFinding(py::module_& m) {
  py::class_<Finding>(m, "Finding",
                      "One typed finding of a run: kind, severity (info, warning, failure), the "
                      "message, and what it names (stage, experiment, segment, parameter, "
                      "output, input; '' when none), the value the rule measured and its "
                      "threshold (NaN when none), repeats folded in (count).")
      .def_property_readonly("kind", [](const Finding& f) { return FindingKindToString(f.kind); })
      .def_property_readonly("severity",
                             [](const Finding& f) { return FindingSeverityToString(f.severity); })
      .def_readonly("message", &Finding::message)
      .def_readonly("stage", &Finding::stage)
      .def_readonly("experiment", &Finding::experiment)
      .def_readonly("segment", &Finding::segment)
      .def_readonly("parameter", &Finding::parameter)
      .def_readonly("output", &Finding::output)
      .def_readonly("input", &Finding::input)
      .def_readonly("value", &Finding::value)
      .def_readonly("threshold", &Finding::threshold)
      .def_readonly("count", &Finding::count)
      .def("__repr__", [](const Finding& f) { return "<vesselid.Finding " + DescribeFinding(f) + ">"; });
}

}  // namespace vesselid::python
