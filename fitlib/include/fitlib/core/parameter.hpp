#pragma once
// Named parameters with unit, bounds, transform and group: what models declare and fitters,
// cards and reports read.
#include <limits>
#include <string>
#include <vector>

namespace fitlib::core {

// How a fitter moves a parameter: `log` keeps a positive scale positive (fitted as log of it).
enum class Transform { linear, log };

struct ParameterSpec {
  std::string name;       // e.g. "G_inf", "tau_3"
  std::string unit;       // e.g. "MPa", "s", "1/degC", "-"
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  Transform transform = Transform::linear;
  std::string group;      // e.g. "elastic", "viscous", "shift", "damage"
  double default_value = 0.0;  // a sensible start when nothing better is known
  // The complex-form moduli are linear in this parameter (a modulus weight such as a Prony
  // coefficient): with every non-linear parameter held fixed, the fit is a linear least squares.
  bool linear = false;
};

// Index of the parameter named `name`, or -1.
int find_parameter(const std::vector<ParameterSpec>& specs, const std::string& name);

}  // namespace fitlib::core
