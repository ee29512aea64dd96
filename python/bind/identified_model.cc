// vesselid.IdentifiedModel: the run's model with its identified parameters, flown on a user's
// inputs as the run flew its records (the run's step bound and interpolation, its
// arithmetic: open_loop_simulation.h), nothing reloaded.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>

#include "engine/data/interpolation.h"
#include "engine/data/trajectory_table.h"
#include "engine/export/model_json.h"
#include "engine/model/open_loop_simulation.h"
#include "python/bind/errors.h"
#include "python/bind/frames.h"
#include "python/bind/types.h"

namespace vesselid::python {
namespace {

constexpr double kDegree = M_PI / 180.0;

bool InDegrees(const IdentifiedModel& m, const std::string& name) {
  return std::find(m.degree_names.begin(), m.degree_names.end(), name) != m.degree_names.end();
}

std::vector<std::string> Names(const std::vector<ModelVariable>& variables) {
  std::vector<std::string> names;
  for (const ModelVariable& v : variables) names.push_back(v.name);
  return names;
}

// Name -> value of `names` as a Series.
py::object Series(const std::vector<ModelVariable>& names, const std::vector<double>& values,
                  const char* title) {
  const py::module_ pandas = py::module_::import("pandas");
  return pandas.attr("Series")(values, py::arg("index") = Names(names), py::arg("name") = title,
                               py::arg("dtype") = "float64");
}

// Replaces values of `variables` by name from `given` (a mapping); a name not among them
// raises KeyError naming the choices. Angles in degrees where `degrees`.
void Override(const IdentifiedModel& m, const std::vector<ModelVariable>& variables,
              const char* what, const py::object& given, bool degrees, std::vector<double>* values) {
  if (given.is_none()) return;
  for (const auto& [key, value] : given.cast<py::dict>()) {
    const std::string name = py::str(key);
    size_t i = 0;
    while (i < variables.size() && variables[i].name != name) ++i;
    if (i == variables.size()) {
      std::string choices;
      for (const ModelVariable& v : variables) choices += (choices.empty() ? "" : ", ") + v.name;
      throw py::key_error(m.model + " has no " + what + " '" + name + "' (" + choices + ")");
    }
    double number = 0.0;
    try {
      number = value.cast<double>();
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(what) + " '" + name + "': a number, not " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    }
    (*values)[i] = number * (degrees && InDegrees(m, name) ? kDegree : 1.0);
  }
}

// How the inputs are interpolated: the run's, or one method for all (a string) or per input
// (a mapping).
std::vector<Interpolation> Methods(const IdentifiedModel& m, const py::object& given) {
  std::vector<std::string> names = m.interpolation;
  if (py::isinstance<py::str>(given)) {
    names.assign(m.inputs.size(), given.cast<std::string>());
  } else if (!given.is_none()) {
    for (const auto& [key, value] : given.cast<py::dict>()) {
      const std::string input = py::str(key);
      size_t i = 0;
      while (i < m.inputs.size() && m.inputs[i].name != input) ++i;
      if (i == m.inputs.size()) throw py::key_error(m.model + " has no input '" + input + "'");
      names[i] = py::str(value);
    }
  }
  std::vector<Interpolation> methods(names.size());
  for (size_t i = 0; i < names.size(); ++i) {
    if (!StringToInterpolation(names[i], &methods[i])) {
      throw PackageError("data", "unknown interpolation '" + names[i] +
                                     "' (zero_order_hold, linear, cubic)");
    }
  }
  return methods;
}

// A step bound given in Python (a number).
double MaxStepOf(const py::object& given) { return py::float_(given).cast<double>(); }

py::object Simulate(const IdentifiedModel& m, const py::object& inputs,
                    const py::object& initial_state, const py::object& parameters,
                    const py::object& max_step, const py::object& interpolation) {
  std::vector<double> values = m.values;
  Override(m, m.parameters, "parameter", parameters, false, &values);
  std::vector<double> x0(m.states.size(), 0.0);
  Override(m, m.states, "state", initial_state, true, &x0);
  // t and the model's inputs, in SI units (other columns are not read).
  Trajectory table;
  table.source = "inputs";
  for (const std::string& name : ColumnNames(inputs, "inputs")) {
    const bool input = std::any_of(m.inputs.begin(), m.inputs.end(),
                                   [&](const ModelVariable& v) { return v.name == name; });
    if (name != "t" && !input) continue;
    table.names.push_back(name);
    table.columns.push_back(ColumnValues(inputs, name, "inputs"));
    if (input && InDegrees(m, name)) {
      for (double& v : table.columns.back()) v *= kDegree;
    }
  }
  Trajectory record, result;
  std::string error;
  if (!TrajectoryFromTable(table, CsvReadOptions(), &record, &error)) {
    throw PackageError("data", error);
  }
  for (size_t c = 0; c < record.names.size(); ++c) {
    if (std::none_of(record.columns[c].begin(), record.columns[c].end(),
                     [](double v) { return std::isfinite(v); })) {
      throw PackageError("data", "inputs: input '" + record.names[c] +
                                     "' has no samples (every value is missing)");
    }
  }
  if (!max_step.is_none() && !(MaxStepOf(max_step) >= 0.0)) {
    throw PackageError("data", "max_step " + std::string(py::str(max_step)) +
                                   ": a step bound in s, >= 0 (0: the median sample interval)");
  }
  OpenLoopOptions options;
  options.substeps = 0;  // steps as the run planned them
  options.max_step = max_step.is_none() ? m.max_step : MaxStepOf(max_step);
  options.input_interpolation = Methods(m, interpolation);
  options.record_states = true;
  bool ok = false;
  {
    py::gil_scoped_release release;
    ok = SimulateOpenLoop(*m.handle, values, x0, record, options, &result, &error);
  }
  if (!ok) throw PackageError("run", error);
  // Angles back in degrees where the data came in degrees (states as "x.<state>").
  for (size_t c = 0; c < result.names.size(); ++c) {
    const std::string& name = result.names[c];
    if (InDegrees(m, name) || (name.rfind("x.", 0) == 0 && InDegrees(m, name.substr(2)))) {
      for (double& v : result.columns[c]) v /= kDegree;
    }
  }
  return FrameOf(result);
}

py::dict Info(const IdentifiedModel& m) {
  py::dict d;
  d["name"] = m.model;
  d["family"] = m.family;
  d["inputs"] = Names(m.inputs);
  d["outputs"] = Names(m.outputs);
  d["states"] = Names(m.states);
  d["parameters"] = Names(m.parameters);
  return d;
}

// The process noise identified with the ship, a row per state: spectral_density, std_error.
py::object ProcessNoiseFrame(const IdentifiedModel& m) {
  using N = ProcessNoise;
  return RowsFrame<N>(
      m.process_noise,
      {{"state", [](const N& n) -> py::object { return py::str(n.state); }},
       {"spectral_density", [](const N& n) -> py::object { return py::float_(n.spectral_density); }},
       {"std_error", [](const N& n) -> py::object { return py::float_(n.std_error); }}},
      "state");
}

py::dict Units(const IdentifiedModel& m) {
  py::dict units;
  for (const auto* variables : {&m.inputs, &m.outputs, &m.states, &m.parameters}) {
    for (const ModelVariable& v : *variables) units[py::str(v.name)] = v.unit;
  }
  return units;
}

}  // namespace

void BindIdentifiedModel(py::module_& m) {
  py::class_<IdentifiedModel, std::shared_ptr<IdentifiedModel>>(
      m, "IdentifiedModel",
      "The run's model with its identified parameters (SI units).\n\n"
      "parameters   Series: every parameter's value (the model's defaults where no stage "
      "estimated one)\n"
      "std_errors   Series (NaN where not estimated); covariance: DataFrame of the estimated "
      "ones, or None\n"
      "max_step, interpolation   how the run integrated: RK4 steps of at most max_step s "
      "(0: the median sample interval), each input interpolated as named\n"
      "degrees      inputs and outputs the run's data gave in degrees (simulate takes and "
      "gives them in degrees)\n"
      "process_noise   DataFrame by state: the spectral density (state unit^2/s) and SE of the "
      "process noise a filter-error stage identified with the ship (empty: none); predict flies "
      "it\n"
      "simulate(inputs, initial_state=None, parameters=None, max_step=None, interpolation=None)"
      "  open loop under `inputs` (t and a column per input) -> DataFrame of t, the inputs, "
      "the outputs and the states ('x.<state>'), as the run simulated its records")
      .def_readonly("name", &IdentifiedModel::model)
      .def_readonly("family", &IdentifiedModel::family)
      .def_readonly("options", &IdentifiedModel::options)
      .def_property_readonly("inputs", [](const IdentifiedModel& x) { return Names(x.inputs); })
      .def_property_readonly("outputs", [](const IdentifiedModel& x) { return Names(x.outputs); })
      .def_property_readonly("states", [](const IdentifiedModel& x) { return Names(x.states); })
      .def_property_readonly("units", &Units)
      .def_property_readonly("info", &Info)
      .def_property_readonly("parameters", [](const IdentifiedModel& x) {
        return Series(x.parameters, x.values, "value");
      })
      .def_property_readonly("std_errors", [](const IdentifiedModel& x) {
        return Series(x.parameters, x.std_errors, "std_error");
      })
      .def_property_readonly("covariance", [](const IdentifiedModel& x) {
        return MatrixFrame(x.covariance, x.covariance_names);
      })
      .def_property_readonly("process_noise", &ProcessNoiseFrame)
      .def_readonly("max_step", &IdentifiedModel::max_step)
      .def_property_readonly("interpolation",
                             [](const IdentifiedModel& x) {
                               py::dict d;
                               for (size_t i = 0; i < x.inputs.size(); ++i) {
                                 d[py::str(x.inputs[i].name)] = x.interpolation[i];
                               }
                               return d;
                             })
      .def_property_readonly("degrees",
                             [](const IdentifiedModel& x) {
                               return std::set<std::string>(x.degree_names.begin(),
                                                            x.degree_names.end());
                             })
      .def("simulate", &Simulate, py::arg("inputs"), py::arg("initial_state") = py::none(),
           py::arg("parameters") = py::none(), py::arg("max_step") = py::none(),
           py::arg("interpolation") = py::none(),
           "Flies the model open loop under `inputs` (a DataFrame or dict with a time column t "
           "and a column per model input, degrees where the run read degrees) from "
           "`initial_state` (zeros where not given) and returns t, the inputs, the outputs and "
           "the states ('x.<state>'). It integrates as the run did (its step bound and "
           "interpolation); `parameters` overrides values by name, `max_step` (s, 0: the "
           "median sample interval) and `interpolation` (a method, or one per input) the "
           "run's settings.")
      .def("to_json", [](const IdentifiedModel& x) { return IdentifiedModelToJson(x).dump(); },
           "model.json's text (`vesselid export --format json`, without ensemble members).")
      .def("__repr__", [](const IdentifiedModel& x) {
        std::string inputs, outputs;
        for (const ModelVariable& v : x.inputs) inputs += (inputs.empty() ? "" : ", ") + v.name;
        for (const ModelVariable& v : x.outputs) outputs += (outputs.empty() ? "" : ", ") + v.name;
        return "<vesselid.IdentifiedModel " + x.model + ": inputs " + inputs + "; outputs " +
               outputs + ">";
      });
}

}  // namespace vesselid::python
