// Linear constraints on control points: derivative conditions on faces and lines (Report V
// Eqs 5.26-5.32, generalised to any axis, order and number of fixed axes) and user constraints.
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/surface/bernstein.hpp"
#include "fitlib/surface/fit.hpp"

namespace fitlib::surface {
namespace {

// Odometer over multi-indices of the given axes (each 0..degree).
bool next_index(std::vector<int>& index, const std::vector<std::size_t>& axes, const Surface& s) {
  for (std::size_t q = axes.size(); q-- > 0;) {
    if (++index[axes[q]] <= s.axes[axes[q]].degree) return true;
    index[axes[q]] = 0;
  }
  return false;
}

std::string describe(const Surface& s, std::size_t axis, int order,
                     const std::vector<std::pair<std::size_t, double>>& fixed) {
  std::ostringstream out;
  out.precision(6);
  out << "d^" << order << "y/du^" << order << " = 0 along '" << s.axes[axis].name << "'";
  std::vector<bool> is_fixed(s.axes.size(), false);
  is_fixed[axis] = true;
  if (!fixed.empty()) out << " where";
  for (std::size_t q = 0; q < fixed.size(); ++q) {
    is_fixed[fixed[q].first] = true;
    out << (q ? "," : "") << " '" << s.axes[fixed[q].first].name << "' u = " << fixed[q].second;
  }
  bool first_free = true;
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    if (is_fixed[k]) continue;
    out << (first_free ? ", for all '" : ", '") << s.axes[k].name << "'";
    first_free = false;
  }
  return out.str();
}

}  // namespace

ConstraintGroup derivative_constraints(const Surface& s, std::size_t axis, int order,
                                       const std::vector<std::pair<std::size_t, double>>& fixed) {
  ConstraintGroup group;
  group.description = describe(s, axis, order, fixed);
  const int d = s.axes[axis].degree;
  if (order < 1 || order > d) return group;  // a derivative beyond the degree vanishes anyway

  std::vector<bool> is_fixed(s.axes.size(), false);
  std::vector<std::size_t> fixed_axes, free_axes;
  std::vector<std::vector<double>> fixed_basis(s.axes.size());
  for (const auto& [k, u] : fixed) {
    is_fixed[k] = true;
    fixed_axes.push_back(k);
    fixed_basis[k].resize(static_cast<std::size_t>(s.axes[k].degree + 1));
    bernstein(s.axes[k].degree, u, fixed_basis[k].data());
  }
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    if (k != axis && !is_fixed[k]) free_axes.push_back(k);

  std::vector<int> index(s.axes.size(), 0);
  do {  // every combination of the free axes' control indices
    for (int i = 0; i + order <= d; ++i) {
      LinearConstraint c;
      for (int k = 0; k <= order; ++k) {
        index[axis] = i + k;
        const double difference = forward_difference_coefficient(order, k);
        for (std::size_t b : fixed_axes) index[b] = 0;
        do {  // Σ over the fixed axes' control indices weighted by their basis at u_b
          double weight = difference;
          for (std::size_t b : fixed_axes) weight *= fixed_basis[b][static_cast<std::size_t>(index[b])];
          if (std::abs(weight) > 1e-15) c.terms.emplace_back(s.flat_index(index), weight);
        } while (next_index(index, fixed_axes, s));
      }
      index[axis] = 0;
      group.equations.push_back(std::move(c));
    }
  } while (next_index(index, free_axes, s));
  return group;
}

namespace {

std::size_t axis_named(const Surface& s, const std::string& name, const std::string& source,
                       const std::string& key) {
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    if (s.axes[k].name == name) return k;
  throw core::InputError("no axis named '" + name + "'", source, 0, 0, key);
}

// {"terms": [{"index": [...], "coefficient": c}, ...], "rhs": r}: one equation on control points.
ConstraintGroup linear_constraint(const nlohmann::json& item, const Surface& s,
                                  const std::string& source, const std::string& key) {
  LinearConstraint c;
  c.rhs = item.value("rhs", 0.0);
  for (std::size_t t = 0; t < item["terms"].size(); ++t) {
    const auto& term = item["terms"][t];
    const auto index = control_point_index_from_json(term.at("index"), s, source,
                                                     key + ".terms[" + std::to_string(t) + "].index");
    c.terms.emplace_back(s.flat_index(index), term.at("coefficient").get<double>());
  }
  ConstraintGroup group;
  group.equations.push_back(c);
  group.description = item.value("description", "user linear constraint");
  return group;
}

// The parameter u of a fixed axis: "start" (0), "end" (1) or a number in [0, 1].
double fixed_parameter(const nlohmann::json& where, const std::string& source,
                       const std::string& key) {
  if (where.is_string() && where == "start") return 0.0;
  if (where.is_string() && where == "end") return 1.0;
  if (where.is_number() && where.get<double>() >= 0.0 && where.get<double>() <= 1.0)
    return where.get<double>();
  throw core::InputError("must be \"start\", \"end\" or a parameter in [0, 1]", source, 0, 0, key);
}

// {"derivative": {"axis": a, "order": n, "at": {axis: u, ...}}}: d^n y/du_a^n = 0 there.
ConstraintGroup derivative_constraint(const nlohmann::json& spec, const Surface& s,
                                      const std::string& source, const std::string& key) {
  const std::size_t axis = axis_named(s, spec.at("axis").get<std::string>(), source, key + ".axis");
  const int order = spec.value("order", 2);
  if (order < 1 || order > s.axes[axis].degree)
    throw core::InputError("order must be between 1 and the axis's degree (" +
                               std::to_string(s.axes[axis].degree) + ")",
                           source, 0, 0, key + ".derivative.order");
  std::vector<std::pair<std::size_t, double>> fixed;
  const nlohmann::json at = spec.value("at", nlohmann::json::object());
  for (const auto& [name, where] : at.items()) {
    const std::size_t b = axis_named(s, name, source, key + ".derivative.at");
    const double u = fixed_parameter(where, source, key + ".derivative.at." + name);
    if (b == axis)
      throw core::InputError("the derivative axis cannot also be fixed", source, 0, 0,
                             key + ".derivative.at." + name);
    fixed.emplace_back(b, u);
  }
  return derivative_constraints(s, axis, order, fixed);
}

}  // namespace

std::vector<ConstraintGroup> parse_user_constraints(const nlohmann::json& j, const Surface& s,
                                                    const std::string& source) {
  std::vector<ConstraintGroup> groups;
  if (j.is_null()) return groups;
  const nlohmann::json& list = j.is_object() && j.contains("constraints") ? j["constraints"] : j;
  if (!list.is_array())
    throw core::InputError("constraints must be an array (or {\"constraints\": [...]})", source, 0,
                           0, "constraints");
  for (std::size_t q = 0; q < list.size(); ++q) {
    const std::string key = "constraints[" + std::to_string(q) + "]";
    const auto& item = list[q];
    ConstraintGroup group;
    try {
      if (item.contains("terms"))
        group = linear_constraint(item, s, source, key);
      else if (item.contains("derivative"))
        group = derivative_constraint(item["derivative"], s, source, key);
      else
        throw core::InputError("a constraint needs \"terms\" or \"derivative\"", source, 0, 0, key);
    } catch (const nlohmann::json::exception& e) {
      throw core::InputError(std::string("malformed constraint: ") + e.what(), source, 0, 0, key);
    }
    group.origin = "user";
    groups.push_back(std::move(group));
  }
  return groups;
}

nlohmann::json read_user_constraints(const std::string& path) {
  try {
    return nlohmann::json::parse(core::read_file(path));
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw core::InputError(std::string("not valid JSON: ") + e.what(), path);
  }
}

}  // namespace fitlib::surface
