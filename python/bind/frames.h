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

}  // namespace vesselid::python
