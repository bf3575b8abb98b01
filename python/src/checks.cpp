// The checks fitcli's options make, for the Python entry points (docs/python.md "Checks"): a
// value out of range is a UsageError naming the argument before any work, never a raw C++
// exception (vector::reserve), a SystemError or a crash.
#include <cmath>

#include "bindings.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::python {

void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) < 0) throw py::error_already_set();  // warnings as errors
}

void require_in(const char* argument, double value, double low, double high) {
  if (std::isfinite(value) && value >= low && value <= high) return;
  throw core::UsageError(std::string(argument) + " must be in [" + core::format_number(low) + ", " +
                         core::format_number(high) + "], got " + core::format_number(value));
}

}  // namespace fitlib::python
