#include "python/bind/frames.h"

#include <pybind11/stl.h>

#include "python/bind/errors.h"

namespace vesselid::python {

std::shared_ptr<Trajectory> TableFromColumns(const std::string& source,
                                             const py::handle& columns) {
  auto table = std::make_shared<Trajectory>();
  table->source = source;
  const py::object names = py::hasattr(columns, "columns") ? columns.attr("columns")
                                                           : py::object(columns.attr("keys")());
  for (const py::handle& key : names) {
    table->names.push_back(py::str(key));
    py::array_t<double, py::array::c_style | py::array::forcecast> array;
    try {
      array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
          columns[key]);
    } catch (const py::error_already_set&) {
    }
    if (!array) {
      throw PackageError("data", source + ": column '" + table->names.back() + "' is not numbers");
    }
    if (array.ndim() != 1) {
      throw PackageError("data", source + ": column '" + table->names.back() +
                                     "' is not one-dimensional");
    }
    table->columns.emplace_back(array.data(), array.data() + array.shape(0));
  }
  return table;
}

py::object Frame(const py::dict& columns, const std::vector<std::string>& order,
                 const std::string& index) {
  const py::module_ pandas = py::module_::import("pandas");
  py::object frame = pandas.attr("DataFrame")(columns, py::arg("columns") = order);
  if (!index.empty()) frame = frame.attr("set_index")(index);
  return frame;
}

py::object FrameOf(const Trajectory& record) {
  py::dict columns;
  std::vector<std::string> order = {"t"};
  columns["t"] = py::array_t<double>(record.t.size(), record.t.data());
  for (size_t c = 0; c < record.names.size(); ++c) {
    columns[py::str(record.names[c])] =
        py::array_t<double>(record.columns[c].size(), record.columns[c].data());
    order.push_back(record.names[c]);
  }
  return Frame(columns, order);
}

}  // namespace vesselid::python
