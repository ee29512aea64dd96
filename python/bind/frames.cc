#include "python/bind/frames.h"

#include <pybind11/stl.h>

#include <cstdint>

#include "python/bind/errors.h"

namespace vesselid::python {

std::vector<std::string> ColumnNames(const py::handle& columns, const std::string& source) {
  std::vector<std::string> names;
  py::object keys;
  if (py::hasattr(columns, "columns")) {
    keys = columns.attr("columns");
  } else if (py::isinstance<py::dict>(columns)) {
    keys = columns.attr("keys")();
  } else {
    throw py::type_error(source + ": a pandas DataFrame or a dict of columns, not " +
                         std::string(py::str(py::type::of(columns).attr("__name__"))));
  }
  for (const py::handle& key : keys) names.push_back(py::str(key));
  return names;
}

std::vector<double> ColumnValues(const py::handle& columns, const std::string& name,
                                 const std::string& source) {
  const py::module_ numpy = py::module_::import("numpy");
  py::array array = numpy.attr("asarray")(columns[py::str(name)]);
  const char kind = array.dtype().kind();
  if (kind == 'M') {  // datetime64: seconds since 1970 (the engine makes times relative)
    array = numpy.attr("asarray")(array.attr("astype")("datetime64[ns]").attr("astype")("int64"));
    const auto ns = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    std::vector<double> values(ns.size());
    for (py::ssize_t i = 0; i < ns.size(); ++i) values[i] = static_cast<double>(ns.data()[i]) / 1e9;
    return values;
  }
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw PackageError("data", source + ": column '" + name + "' holds " +
                                   std::string(py::str(array.dtype())) + " values, not numbers");
  }
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (values.ndim() != 1) {
    throw PackageError("data", source + ": column '" + name + "' is not one-dimensional");
  }
  return std::vector<double>(values.data(), values.data() + values.shape(0));
}

std::shared_ptr<Trajectory> TableFromColumns(const std::string& source,
                                             const py::handle& columns) {
  auto table = std::make_shared<Trajectory>();
  table->source = source;
  for (const std::string& name : ColumnNames(columns, source)) {
    table->names.push_back(name);
    table->columns.push_back(ColumnValues(columns, name, source));
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

py::object MatrixFrame(const Eigen::MatrixXd& c, const std::vector<std::string>& names) {
  if (c.size() == 0) return py::none();
  const py::module_ pandas = py::module_::import("pandas");
  py::array_t<double> matrix({c.rows(), c.cols()});
  auto view = matrix.mutable_unchecked<2>();
  for (int r = 0; r < c.rows(); ++r) {
    for (int k = 0; k < c.cols(); ++k) view(r, k) = c(r, k);
  }
  return pandas.attr("DataFrame")(matrix, py::arg("index") = names, py::arg("columns") = names);
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
