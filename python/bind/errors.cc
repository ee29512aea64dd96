#include "python/bind/errors.h"

namespace py = pybind11;

namespace vesselid::python {

void RegisterErrors() {
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) std::rethrow_exception(raised);
    } catch (const PackageError& e) {
      if (e.kind == "interrupted") {
        PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        return;
      }
      const py::module_ errors = py::module_::import("vesselid._errors");
      const char* name = e.kind == "config" ? "ConfigError"
                         : e.kind == "data" ? "DataError"
                                            : "RunError";
      PyErr_SetString(errors.attr(name).ptr(), e.what());
    }
  });
}

}  // namespace vesselid::python
