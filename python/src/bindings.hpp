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
#include <string>
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
// A temperature that may be left out: None is NaN, read by the library as the reference
// temperature (the default of every entry point that takes one).
double optional_temperature(const py::handle& value, const char* argument = "temperature_C");



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
