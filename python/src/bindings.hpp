#pragma once
// Shared pieces of the Python module (docs/python.md): JSON ↔ Python objects, vectors ↔ NumPy,
// and one bind function per group of library modules (one translation unit each).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include "fitlib/model/model.hpp"
#include "fitlib/scene/results.hpp"
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace fitlib::python {

namespace py = pybind11;

// JSON documents cross the boundary as Python dicts/lists through Python's json module (exact
// for doubles: both sides print the shortest round-trip form).
py::object to_python(const nlohmann::json& j);
nlohmann::json to_json(const py::handle& object);

// A copy of `v` as a 1-D NumPy array.
py::array_t<double> to_array(const std::vector<double>& v);
// Any array-like of numbers (scalar, list, NumPy array) flattened to doubles; TypeError naming
// `argument` for None, text, bools or other objects (NumPy's float conversion made None a NaN:
// card.eval(None) answered "nan Hz").
std::vector<double> to_vector(const py::handle& object, const char* argument = nullptr);
// `value` as a NumPy array of integer or floating dtype; TypeError naming `argument` otherwise.
py::array numbers(const py::handle& value, const char* argument);
// One number (int, float, NumPy scalar); TypeError naming `argument` for None or anything else.
double number(const py::handle& value, const char* argument);

// True or False (a NumPy bool too); TypeError naming `argument` for None, 0, 1 or any other object
// (pybind11's conversion read None as False and any number or object with __bool__ as its truth).
bool boolean(const py::handle& value, const char* argument);

// The value of an options field or an entry point's argument `name` from Python: a number through
// `number`, a bool through `boolean`, None or a number for std::optional<double>, any other type
// without pybind11's conversions (True is not 1, 2.5 is not an int); a TypeError naming it otherwise
// (pybind11's own, "incompatible function arguments", listed the signature and named nothing).
template <typename T>
T field_value(const py::handle& value, const char* name) {
  if constexpr (std::is_same_v<T, double>) {
    return number(value, name);
  } else if constexpr (std::is_same_v<T, bool>) {
    return boolean(value, name);
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return value.is_none() ? std::nullopt : std::optional<double>(number(value, name));
  } else {
    py::detail::make_caster<T> caster;
    py::object v = py::reinterpret_borrow<py::object>(value);
    // NumPy integers as Python ints (without conversion an unsigned field refused np.int64(3))
    if (std::is_integral_v<T> && PyIndex_Check(value.ptr()))
      v = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
    if (!v) throw py::error_already_set();
    if (!py::isinstance<py::bool_>(value) && caster.load(v, false))
      return py::detail::cast_op<T>(std::move(caster));
    throw py::type_error(std::string(name) + " must be " + decltype(caster)::name.text + ", got " +
                         std::string(py::repr(value)));
  }
}

// A tag: Checked<ArrayLike> is a number or an array of numbers (a list, a NumPy array) that the
// body reads with `numbers` or `to_vector` and the argument's name.
struct ArrayLike {};

// The type a Checked<T> argument shows in its signature: T's own, or NumPy's name of an array-like.
template <typename T>
struct python_type {
  static constexpr auto name = py::detail::make_caster<T>::name;
};
template <>
struct python_type<ArrayLike> {
  static constexpr auto name = py::detail::const_name("numpy.typing.ArrayLike");
};
template <>
struct python_type<std::optional<ArrayLike>> {
  static constexpr auto name = py::detail::const_name("Optional[numpy.typing.ArrayLike]");
};

// An entry point's argument that its body checks by name with field_value (`get`) or, an
// array-like, with `numbers`: pybind11 hands any object over (its own refusal named no argument,
// its conversion read None as False) and the signature shows the Python type (float, int, bool,
// Optional[float], numpy.typing.ArrayLike), not `object`.
template <typename T>
struct Checked {
  py::object object;
  T get(const char* name) const { return field_value<T>(object, name); }
};

using Array = Checked<ArrayLike>;                         // a number or an array of numbers
using OptionalArray = Checked<std::optional<ArrayLike>>;  // the same, or None

// A temperature that may be left out: None is NaN, read by the library as the reference
// temperature (the default of every entry point that takes one).
double optional_temperature(const Checked<std::optional<double>>& value, const char* argument = "temperature_C");

// A property `name` of an options class whose setter `set(o, value)` gets field_value's value.
template <typename T, typename S, typename Get, typename Set>
void def_field(py::class_<S>& c, const char* name, Get get, Set set) {
  c.def_property(name, get, [name, set](S& o, const py::handle& v) { set(o, field_value<T>(v, name)); });
}
// def_readwrite with field_value's checks.
template <typename S, typename T>
void def_field(py::class_<S>& c, const char* name, T S::*member) {
  def_field<T>(c, name, [member](const S& o) { return o.*member; }, [member](S& o, T v) { o.*member = std::move(v); });
}



// Python's warnings.warn(message) (what fitcli prints as "warning: ..." on stderr).
void warn(const std::string& message);

// Refusals before work, as fitcli's option checks (docs/python.md "Checks"): UsageError naming the
// argument when `value` is outside [low, high] (or not finite).
void require_in(const char* argument, double value, double low, double high);

// Storage, loss, tan δ and mean modulus of `m` with parameters `p` over NumPy-broadcast arrays
// of frequency, temperature (None = the reference) and strain amplitude; mode "" = native.
// `at`, when given, answers each condition instead of the model (Card.eval: window, conversion).
using ModuliAt = std::function<model::Moduli<double>(const model::TestCondition&)>;
py::dict moduli_arrays(const model::Model& m, const std::vector<double>& p, const py::object& f,
                       const py::object& T, const py::object& amplitude, const std::string& mode,
                       const std::string& orientation, const ModuliAt& at = {});

void bind_errors(py::module_& m);
void bind_data_model(py::module_& m);
void bind_fit_card(py::module_& m);
void bind_surface_point_scene(py::module_& m);
void bind_master_relaxation(py::module_& m);  // master_relaxation.cpp
void bind_segment_life(py::module_& m);       // segment_life.cpp

// The life of a scene result as a dict (None when it did not run); segment_life.cpp.
py::object life_dict(const scene::SceneResult& result);
void bind_sweep(py::module_& m);
void bind_hyperelastic(py::module_& m);       // hyperelastic.cpp

}  // namespace fitlib::python

namespace pybind11::detail {
// Checked<T> takes every object (the body's check names the argument) and is named as T.
template <typename T>
struct type_caster<fitlib::python::Checked<T>> {
  PYBIND11_TYPE_CASTER(fitlib::python::Checked<T>, fitlib::python::python_type<T>::name);
  bool load(handle src, bool) {
    value.object = reinterpret_borrow<object>(src);
    return true;
  }
};
}  // namespace pybind11::detail
