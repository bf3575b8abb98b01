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

py::array numbers(const py::handle& value, const char* argument) {
  if (!value.is_none() && !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value)) {
    const auto a = py::array::ensure(py::module_::import("numpy").attr("asarray")(value));
    const char kind = a ? a.dtype().kind() : 'O';
    if (kind == 'i' || kind == 'u' || kind == 'f') return a;  // not 'b', 'U', 'O' (None inside a list)
  }
  throw py::type_error(std::string(argument ? argument : "the argument") +
                       " must be a number or an array of numbers, got " + std::string(py::repr(value)));
}

double number(const py::handle& value, const char* argument) {
  const py::array a = numbers(value, argument);
  if (a.ndim() != 0)
    throw py::type_error(std::string(argument) + " must be one number, got " + std::string(py::repr(value)));
  return a.attr("item")().cast<double>();
}

bool boolean(const py::handle& value, const char* argument) {
  if (value.ptr() == Py_True || value.ptr() == Py_False) return value.ptr() == Py_True;
  const std::string type = Py_TYPE(value.ptr())->tp_name;  // numpy.bool_ (numpy.bool from NumPy 2)
  if (type == "numpy.bool_" || type == "numpy.bool") return PyObject_IsTrue(value.ptr()) == 1;
  throw py::type_error(std::string(argument) + " must be a bool (True or False), got " + std::string(py::repr(value)));
}

double optional_temperature(const Checked<std::optional<double>>& value, const char* argument) {
  return value.get(argument).value_or(std::nan(""));
}

}  // namespace fitlib::python
