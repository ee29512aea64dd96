// Tables between the engine and Python: records as {column: float64 array} (DataFrames or
// dicts of array-likes in, copied), pandas DataFrames out.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "Eigen/Core"
#include "engine/data/trajectory.h"

namespace vesselid::python {

namespace py = pybind11;

// The column names of a DataFrame or a dict of columns; TypeError for anything else.
std::vector<std::string> ColumnNames(const py::handle& columns, const std::string& source);

// One column as doubles: numbers and booleans as they are, datetime64 as seconds since 1970;
// text or objects are refused (PackageError "data").
std::vector<double> ColumnValues(const py::handle& columns, const std::string& name,
                                 const std::string& source);

// A table of the named columns (a DataFrame, or a dict of 1-D arrays): copied, as the
// engine keeps its own record while it works. Throws PackageError("data") naming `source`.
std::shared_ptr<Trajectory> TableFromColumns(const std::string& source, const py::handle& columns);

// A record as a DataFrame: t first, then its columns.
py::object FrameOf(const Trajectory& record);

// A square matrix as a DataFrame indexed and headed by `names`, or None when it is empty.
py::object MatrixFrame(const Eigen::MatrixXd& matrix, const std::vector<std::string>& names);

// A DataFrame of `columns` (name -> list or array) in `order`, indexed by `index` ("" none).
py::object Frame(const py::dict& columns, const std::vector<std::string>& order,
                 const std::string& index = "");

// A DataFrame of `rows`: one column per (name, the row's value of it), in that order, indexed
// by the column named `index` ("" none). The engine's records of a run (estimates, auto's
// candidates, predictions through the filter, process noise) as tables.
template <class Row>
struct Column {
  std::string name;
  py::object (*value)(const Row&);
};
template <class Row>
py::object RowsFrame(const std::vector<Row>& rows, const std::vector<Column<Row>>& columns,
                     const std::string& index = "") {
  py::dict table;
  std::vector<std::string> order;
  for (const Column<Row>& c : columns) {
    py::list values;
    for (const Row& row : rows) values.append(c.value(row));
    table[py::str(c.name)] = values;
    order.push_back(c.name);
  }
  return Frame(table, order, index);
}

}  // namespace vesselid::python
