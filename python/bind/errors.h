// Errors the binding raises as the package's exception classes (vesselid/_errors.py):
// throw PackageError{"config" | "data" | "run" | "interrupted", message}.
#pragma once

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

namespace vesselid::python {

struct PackageError : std::runtime_error {
  PackageError(std::string kind, const std::string& message)
      : std::runtime_error(message), kind(std::move(kind)) {}
  std::string kind;
};

// Translates PackageError into ConfigError, DataError, RunError or KeyboardInterrupt.
void RegisterErrors();

}  // namespace vesselid::python
