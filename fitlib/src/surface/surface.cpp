// Bezier surface: axes, evaluation (value, gradient), JSON (docs/formats.md §4).
#include "fitlib/surface/surface.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"
#include "fitlib/surface/bernstein.hpp"

namespace fitlib::surface {

const char* to_string(Transform t) { return t == Transform::log10 ? "log10" : "linear"; }

Transform parse_transform(const std::string& text) {
  if (text == "linear" || text == "lin") return Transform::linear;
  if (text == "log10" || text == "log") return Transform::log10;
  throw core::UsageError("unknown axis transform '" + text + "' (use linear or log10)");
}

Transform default_transform(const std::string& axis_name) {
  std::string lower = axis_name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("frequency") != std::string::npos ? Transform::log10 : Transform::linear;
}

double Axis::coordinate(double x) const {
  if (transform == Transform::linear) return x;
  if (!(x > 0.0)) {
    std::ostringstream msg;
    msg << "axis '" << name << "' is log10, so its values must be positive; got " << x;
    throw core::InputError(msg.str(), {}, 0, 0, name);
  }
  return std::log10(x);
}

double Axis::parameter(double x) const {
  const double c0 = coordinate(start), c1 = coordinate(end);
  return c1 == c0 ? 0.0 : (coordinate(x) - c0) / (c1 - c0);
}

double Axis::parameter_derivative(double x) const {
  const double c0 = coordinate(start), c1 = coordinate(end);
  if (c1 == c0) return 0.0;
  const double dcoord_dx = transform == Transform::linear ? 1.0 : 1.0 / (x * std::log(10.0));
  return dcoord_dx / (c1 - c0);
}

bool Axis::contains(double x) const {
  if (transform == Transform::log10 && !(x > 0.0)) return false;
  const double c0 = coordinate(start), c1 = coordinate(end), c = coordinate(x);
  const double tolerance = 1e-9 * std::max({std::abs(c1 - c0), std::abs(c0), std::abs(c1), 1e-300});
  return c >= c0 - tolerance && c <= c1 + tolerance;
}

double Axis::value_at(double u) const {
  const double c = coordinate(start) + u * (coordinate(end) - coordinate(start));
  return transform == Transform::linear ? c : std::pow(10.0, c);
}

int Axis::nearest_level(double x) const {
  int best = 0;
  for (std::size_t l = 1; l < levels.size(); ++l)
    if (std::abs(coordinate(levels[l]) - coordinate(x)) <
        std::abs(coordinate(levels[static_cast<std::size_t>(best)]) - coordinate(x)))
      best = static_cast<int>(l);
  return best;
}

std::size_t Surface::size() const {
  std::size_t p = 1;
  for (const auto& a : axes) p *= static_cast<std::size_t>(a.degree + 1);
  return p;
}

std::size_t Surface::flat_index(const std::vector<int>& index) const {
  std::size_t flat = 0;
  for (std::size_t k = 0; k < axes.size(); ++k)
    flat = flat * static_cast<std::size_t>(axes[k].degree + 1) + static_cast<std::size_t>(index[k]);
  return flat;
}

std::vector<int> Surface::multi_index(std::size_t flat) const {
  std::vector<int> index(axes.size());
  for (std::size_t k = axes.size(); k-- > 0;) {
    const auto n = static_cast<std::size_t>(axes[k].degree + 1);
    index[k] = static_cast<int>(flat % n);
    flat /= n;
  }
  return index;
}

namespace {

// Contracts the control points with one basis vector per axis, last axis first, in a scratch
// buffer: about p (1 + 1/(d+1) + ...) multiply-adds, no allocation after the first call.
double contract(const Surface& s, const std::vector<const double*>& basis,
                std::vector<double>& scratch) {
  const std::size_t n = s.axes.size();
  if (n == 0) return s.control_points.size() ? s.control_points[0] : 0.0;
  std::size_t length = static_cast<std::size_t>(s.control_points.size());
  const double* source = s.control_points.data();
  scratch.resize(std::max<std::size_t>(length, 1));
  double* work = scratch.data();
  for (std::size_t k = n; k-- > 0;) {
    const std::size_t width = static_cast<std::size_t>(s.axes[k].degree + 1);
    const double* b = basis[k];
    const std::size_t outer = length / width;
    for (std::size_t q = 0; q < outer; ++q) {  // in place is safe: q <= q * width
      const double* row = source + q * width;
      double sum = 0.0;
      for (std::size_t l = 0; l < width; ++l) sum += row[l] * b[l];
      work[q] = sum;
    }
    source = work;
    length = outer;
  }
  return work[0];
}

struct Scratch {
  std::vector<double> basis, derivative, work;
  std::vector<const double*> pointers;
};

Scratch& scratch_for(const Surface& s) {
  thread_local Scratch scratch;
  std::size_t total = 0;
  for (const auto& a : s.axes) total += static_cast<std::size_t>(a.degree + 1);
  scratch.basis.resize(total);
  scratch.derivative.resize(total);
  scratch.pointers.resize(s.axes.size());
  return scratch;
}

}  // namespace

double evaluate_at_parameters(const Surface& s, const double* u, double* gradient_du) {
  Scratch& w = scratch_for(s);
  std::size_t offset = 0;
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    const int d = s.axes[k].degree;
    if (gradient_du)
      bernstein_with_derivative(d, u[k], &w.basis[offset], &w.derivative[offset]);
    else
      bernstein(d, u[k], &w.basis[offset]);
    w.pointers[k] = &w.basis[offset];
    offset += static_cast<std::size_t>(d + 1);
  }
  const double value = contract(s, w.pointers, w.work);
  if (gradient_du) {
    offset = 0;
    for (std::size_t k = 0; k < s.axes.size(); ++k) {
      w.pointers[k] = &w.derivative[offset];
      gradient_du[k] = contract(s, w.pointers, w.work);
      w.pointers[k] = &w.basis[offset];
      offset += static_cast<std::size_t>(s.axes[k].degree + 1);
    }
  }
  return value;
}

double dependent_value(const Surface& s, double v) {
  return s.dependent_transform == Transform::log10 ? std::pow(10.0, v) : v;
}

bool Surface::contains(const double* x) const {
  for (std::size_t k = 0; k < axes.size(); ++k)
    if (!axes[k].contains(x[k])) return false;
  return true;
}

namespace {
void check_inside(const Surface& s, const double* x, bool allow, bool* extrapolated) {
  bool outside = false;
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    if (s.axes[k].contains(x[k])) continue;
    outside = true;
    if (!allow) {
      std::ostringstream msg;
      msg.precision(10);
      msg << "axis '" << s.axes[k].name << "' = " << x[k] << " lies outside the surface's interval ["
          << s.axes[k].start << ", " << s.axes[k].end
          << "]; a fitted surface interpolates only (Report V §5.1); pass allow_extrapolation "
             "(--allow-extrapolation) to evaluate anyway";
      throw core::InputError(msg.str(), {}, 0, 0, s.axes[k].name);
    }
  }
  if (extrapolated) *extrapolated = outside;
}
}  // namespace

double Surface::value(const double* x, bool allow_extrapolation, bool* extrapolated) const {
  check_inside(*this, x, allow_extrapolation, extrapolated);
  thread_local std::vector<double> u;
  u.resize(axes.size());
  for (std::size_t k = 0; k < axes.size(); ++k) u[k] = axes[k].parameter(x[k]);
  return dependent_value(*this, evaluate_at_parameters(*this, u.data(), nullptr));
}

Evaluation Surface::evaluate(const double* x, bool allow_extrapolation) const {
  Evaluation e;
  check_inside(*this, x, allow_extrapolation, &e.extrapolated);
  const std::size_t n = axes.size();
  std::vector<double> u(n), du(n);
  for (std::size_t k = 0; k < n; ++k) u[k] = axes[k].parameter(x[k]);
  e.value = dependent_value(*this, evaluate_at_parameters(*this, u.data(), du.data()));
  // d(10^v)/dx = ln 10 · y · dv/dx for a log10 dependent.
  const double chain = dependent_transform == Transform::log10 ? std::log(10.0) * e.value : 1.0;
  e.gradient.resize(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k)
    e.gradient[static_cast<Eigen::Index>(k)] = chain * du[k] * axes[k].parameter_derivative(x[k]);
  return e;
}

// ---- JSON ----

namespace {
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json equation_to_json(const Surface& s, const LinearConstraint& c) {
  nlohmann::json terms = nlohmann::json::array();
  for (const auto& [flat, coefficient] : c.terms)
    terms.push_back({{"index", s.multi_index(flat)}, {"coefficient", coefficient}});
  return {{"terms", terms}, {"rhs", c.rhs}};
}

template <typename T>
T required(const nlohmann::json& j, const char* key, const std::string& source,
           const std::string& path) {
  if (!j.is_object() || !j.contains(key))
    throw core::InputError("missing key", source, 0, 0, path + key);
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw core::InputError(std::string("wrong type: ") + e.what(), source, 0, 0, path + key);
  }
}
}  // namespace

nlohmann::json surface_to_json(const Surface& s) {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : s.axes)
    axes.push_back({{"name", a.name},
                    {"unit", a.unit},
                    {"transform", to_string(a.transform)},
                    {"interval", {a.start, a.end}},
                    {"degree", a.degree},
                    {"levels", a.levels},
                    {"level_count", a.level_count},
                    {"scattered", a.scattered}});
  nlohmann::json constraints = nlohmann::json::array();
  for (const auto& g : s.constraints) {
    nlohmann::json equations = nlohmann::json::array();
    for (const auto& c : g.equations) equations.push_back(equation_to_json(s, c));
    constraints.push_back({{"origin", g.origin},
                           {"description", g.description},
                           {"cells", g.cells},
                           {"equations", equations}});
  }
  const Statistics& st = s.statistics;
  return {{"schema", Surface::kSchema},
          {"name", s.name},
          {"dependent", {{"name", s.dependent_name}, {"unit", s.dependent_unit},
                         {"transform", to_string(s.dependent_transform)}}},
          {"axes", axes},
          {"control_points",
           {{"order", "row-major over (i_1, ..., i_n), last axis fastest"},
            {"values", std::vector<double>(s.control_points.data(),
                                           s.control_points.data() + s.control_points.size())}}},
          {"level_grid", s.level_grid},
          {"missing_cells", s.missing_cells},
          {"constraints", constraints},
          {"statistics",
           {{"N", st.n_points},
            {"p", st.n_parameters},
            {"residual_dof", st.residual_dof},
            {"R", number_or_null(st.R)},
            {"s", number_or_null(st.s)},
            {"max_relative_error", number_or_null(st.max_relative_error)},
            {"max_relative_error_row", st.max_relative_error_row},
            {"ss_residual", st.ss_residual},
            {"ss_total", st.ss_total},
            {"occupied_cells", st.n_occupied_cells},
            {"range",
             {{"data_min", number_or_null(st.data_min)},
              {"data_max", number_or_null(st.data_max)},
              {"surface_min", number_or_null(st.surface_min)},
              {"surface_min_at", st.surface_min_at},
              {"surface_max", number_or_null(st.surface_max)},
              {"surface_max_at", st.surface_max_at}}},
            {"warnings", statistics_warnings(s)}}},
          {"provenance", s.provenance}};
}

namespace {
// "-415.2 at (temperature_C 100, frequency_Hz 100)".
std::string extreme_text(const Surface& s, double value, const std::vector<double>& at) {
  std::ostringstream out;
  out.precision(4);
  out << value << " at (";
  for (std::size_t k = 0; k < s.axes.size() && k < at.size(); ++k) out << (k ? ", " : "") << s.axes[k].name << " " << at[k];
  out << ")";
  return out.str();
}

// The empty cell of the level grid nearest to x (each axis's nearest level), if x lies in one.
const std::vector<int>* empty_cell_at(const Surface& s, const std::vector<double>& x) {
  if (!s.level_grid || x.size() != s.axes.size()) return nullptr;
  std::vector<int> cell;
  for (std::size_t k = 0; k < s.axes.size(); ++k) {
    const Axis& a = s.axes[k];
    if (a.scattered || a.levels.empty()) {
      cell.push_back(-1);
      continue;
    }
    cell.push_back(a.nearest_level(x[k]));
  }
  const auto found = std::find(s.missing_cells.begin(), s.missing_cells.end(), cell);
  return found == s.missing_cells.end() ? nullptr : &*found;
}

}  // namespace

// The range check: a sign the data never take, or a swing beyond kRangeOvershoot of their range.
std::string range_warning(const Surface& s) {
  const Statistics& st = s.statistics;
  if (!std::isfinite(st.surface_min) || !std::isfinite(st.surface_max) || !std::isfinite(st.data_min)) return "";
  // (Round-off floor: constant data give a zero range, and a surface through them differs by 1e-15.)
  const double margin = std::max(kRangeOvershoot * (st.data_max - st.data_min),
                                 1e-9 * std::max(std::abs(st.data_min), std::abs(st.data_max)));
  const bool negative = st.data_min > 0.0 && st.surface_min <= -1e-12 * st.data_max;
  const bool positive = st.data_max < 0.0 && st.surface_max >= -1e-12 * st.data_min;
  const bool below = st.surface_min < st.data_min - margin, above = st.surface_max > st.data_max + margin;
  if (!(negative || positive || below || above)) return "";
  std::ostringstream out;
  out.precision(4);
  out << "the surface reaches ";
  const bool low = negative || below, high = positive || above;
  if (low) out << extreme_text(s, st.surface_min, st.surface_min_at);
  if (low && high) out << " and ";
  if (high) out << extreme_text(s, st.surface_max, st.surface_max_at);
  out << ", where the data's " << s.dependent_name << " lie in [" << st.data_min << ", " << st.data_max << "]";
  if (negative || positive) out << " and never change sign";
  const std::vector<int>* empty = empty_cell_at(s, low ? st.surface_min_at : st.surface_max_at);
  std::vector<std::string> remedies;
  if (empty) {
    out << ": it lies in an empty cell of the level grid (levels";
    for (const int l : *empty) out << " " << l;
    out << ", 0-based), where the surface shows the missing-cell constraint, not a measurement; ";
    remedies = {"measure that cell", "constrain it (--constraints)"};
  } else {
    out << ": the surface swings between the data, so R and the errors at the points do not describe it; ";
    remedies = {"add levels"};
  }
  if (s.dependent_transform == Transform::linear && st.data_min > 0.0)
    remedies.push_back("fit log10 of the values (--y " + s.dependent_name + ":log)");
  remedies.push_back("lower a degree (--degree)");
  for (std::size_t i = 0; i < remedies.size(); ++i)
    out << (i == 0 ? "" : i + 1 == remedies.size() ? " or " : ", ") << remedies[i];
  return out.str();
}

std::vector<std::string> statistics_warnings(const Surface& s) {
  const Statistics& st = s.statistics;
  std::vector<std::string> out;
  if (st.residual_dof == 0 && st.n_points > 0)
    out.push_back("no residual degrees of freedom (N = " + std::to_string(st.n_points) + ", p = " +
                  std::to_string(st.n_parameters) +
                  "): the surface passes through every point whatever it is between them, so R and s say nothing "
                  "about it; lower a degree (--degree) or measure more levels");
  if (std::string range = range_warning(s); !range.empty()) out.push_back(std::move(range));
  return out;
}

namespace {

// A transform as the JSON stores it (only the full names), InputError naming `key` otherwise.
Transform stored_transform(const std::string& text, const std::string& source, const std::string& key) {
  if (text != "linear" && text != "log10")
    throw core::InputError("transform must be linear or log10", source, 0, 0, key);
  return parse_transform(text);
}

Axis axis_from_json(const nlohmann::json& j, const std::string& source, const std::string& path) {
  Axis a;
  a.name = required<std::string>(j, "name", source, path);
  a.unit = j.value("unit", "");
  a.transform = stored_transform(required<std::string>(j, "transform", source, path), source, path + "transform");
  const auto interval = required<std::vector<double>>(j, "interval", source, path);
  if (interval.size() != 2 || !(interval[0] <= interval[1]) || !std::isfinite(interval[1] - interval[0]))
    throw core::InputError("must be [start, end] with start <= end", source, 0, 0, path + "interval");
  a.start = interval[0];
  a.end = interval[1];
  if (a.transform == Transform::log10 && !(a.start > 0.0))
    throw core::InputError("a log10 axis needs a positive interval", source, 0, 0, path + "interval");
  a.degree = static_cast<int>(core::json_integer(required<nlohmann::json>(j, "degree", source, path), 0, kMaxDegree,
                                                 source, path + "degree"));
  if (j.contains("levels")) a.levels = j["levels"].get<std::vector<double>>();
  a.level_count = j.value("level_count", a.levels.size());
  a.scattered = j.value("scattered", false);
  return a;
}

// Empty cells of a constraint group: level indices per axis, whole numbers within int's range.
std::vector<std::vector<int>> cells_from_json(const nlohmann::json& cells, const std::string& source) {
  std::vector<std::vector<int>> out;
  for (const auto& cell : cells) {
    std::vector<int> levels;
    for (const auto& level : cell)
      levels.push_back(static_cast<int>(core::json_integer(level, 0, std::numeric_limits<int>::max(),
                                                           source, "constraints[].cells")));
    out.push_back(levels);
  }
  return out;
}

// Constraint groups on the control points of `s` (its axes read already).
std::vector<ConstraintGroup> constraints_from_json(const nlohmann::json& groups, const Surface& s,
                                                   const std::string& source) {
  std::vector<ConstraintGroup> out;
  try {
    for (const auto& g : groups) {
      ConstraintGroup group;
      group.origin = g.value("origin", "");
      group.description = g.value("description", "");
      if (g.contains("cells")) group.cells = cells_from_json(g["cells"], source);
      for (const auto& e : g.value("equations", nlohmann::json::array())) {
        LinearConstraint c;
        c.rhs = e.value("rhs", 0.0);
        for (const auto& t : e.value("terms", nlohmann::json::array())) {
          const auto index = control_point_index_from_json(t.at("index"), s, source,
                                                           "constraints[].equations[].terms[].index");
          c.terms.emplace_back(s.flat_index(index), t.at("coefficient").get<double>());
        }
        group.equations.push_back(c);
      }
      out.push_back(group);
    }
  } catch (const nlohmann::json::exception& e) {
    throw core::InputError(std::string("malformed constraints: ") + e.what(), source, 0, 0, "constraints");
  }
  return out;
}

// A number of an object, NaN when absent or null.
double number_or_nan(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::numeric_limits<double>::quiet_NaN();
}

Statistics statistics_from_json(const nlohmann::json& st) {
  auto number = [&](const char* key) { return number_or_nan(st, key); };
  Statistics out;
  out.n_points = st.value("N", std::size_t{0});
  out.n_parameters = st.value("p", std::size_t{0});
  out.residual_dof = st.value("residual_dof", std::size_t{0});
  out.R = number("R");
  out.s = number("s");
  out.max_relative_error = number("max_relative_error");
  out.max_relative_error_row = st.value("max_relative_error_row", std::size_t{0});
  out.ss_residual = number("ss_residual");
  out.ss_total = number("ss_total");
  out.n_occupied_cells = st.value("occupied_cells", std::size_t{0});
  if (st.contains("range") && st["range"].is_object()) {
    const nlohmann::json& r = st["range"];
    out.data_min = number_or_nan(r, "data_min"), out.data_max = number_or_nan(r, "data_max");
    out.surface_min = number_or_nan(r, "surface_min"), out.surface_max = number_or_nan(r, "surface_max");
    out.surface_min_at = r.value("surface_min_at", std::vector<double>{});
    out.surface_max_at = r.value("surface_max_at", std::vector<double>{});
  }
  return out;
}

}  // namespace

Surface surface_from_json(const nlohmann::json& j, const std::string& source) {
  std::string at = "name";  // the key being read, for a JSON type error (it named none)
  try {
    Surface s;
    const auto schema = required<std::string>(j, "schema", source, "");
    if (schema != Surface::kSchema)
      throw core::InputError("unknown schema '" + schema + "' (expected " + Surface::kSchema + ")",
                             source, 0, 0, "schema");
    s.name = j.value("name", "");
    at = "dependent";
    if (j.contains("dependent")) {
      s.dependent_name = j["dependent"].value("name", "");
      s.dependent_unit = j["dependent"].value("unit", "");
      s.dependent_transform = stored_transform(j["dependent"].value("transform", "linear"), source, "dependent.transform");
    }
    const auto axes = required<nlohmann::json>(j, "axes", source, "");
    if (!axes.is_array() || axes.empty() || axes.size() > kMaxAxes)
      throw core::InputError("must be an array of 1 to " + std::to_string(kMaxAxes) + " axes", source, 0, 0, "axes");
    double control_point_count = 1.0;
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const std::string path = "axes[" + std::to_string(k) + "].";
      s.axes.push_back(axis_from_json(axes[k], source, path));
      control_point_count *= s.axes.back().degree + 1;
      if (control_point_count > kMaxControlPoints)
        throw core::InputError("the degrees need more than " + std::to_string(kMaxControlPoints) +
                                   " control points", source, 0, 0, path + "degree");
    }
    const auto cp = required<nlohmann::json>(j, "control_points", source, "");
    const auto values = required<std::vector<double>>(cp, "values", source, "control_points.");
    if (values.size() != s.size())
      throw core::InputError("has " + std::to_string(values.size()) + " values; the degrees need " +
                                 std::to_string(s.size()),
                             source, 0, 0, "control_points.values");
    s.control_points = Eigen::Map<const Eigen::VectorXd>(values.data(),
                                                         static_cast<Eigen::Index>(values.size()));
    at = "level_grid";
    s.level_grid = j.value("level_grid", false);
    at = "missing_cells";
    if (j.contains("missing_cells"))
      s.missing_cells = j["missing_cells"].get<std::vector<std::vector<int>>>();
    at = "constraints";
    if (j.contains("constraints")) s.constraints = constraints_from_json(j["constraints"], s, source);
    at = "statistics";
    if (j.contains("statistics")) s.statistics = statistics_from_json(j["statistics"]);
    if (j.contains("provenance")) s.provenance = j["provenance"];
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw core::InputError(std::string("wrong type: ") + e.what(), source, 0, 0, at);
  }
}

std::vector<int> control_point_index_from_json(const nlohmann::json& index, const Surface& s,
                                               const std::string& source, const std::string& key) {
  if (!index.is_array() || index.size() != s.axes.size())
    throw core::InputError("a control-point index needs one whole number per axis (" +
                               std::to_string(s.axes.size()) + ")", source, 0, 0, key);
  std::vector<int> out;
  for (std::size_t k = 0; k < index.size(); ++k)
    out.push_back(static_cast<int>(core::json_integer(index[k], 0, s.axes[k].degree, source,
                                                      key + "[" + std::to_string(k) + "]")));
  return out;
}

Surface load_surface(const std::string& path) {
  return surface_from_json(core::load_json(path), path);
}

void save_surface(const std::string& path, const Surface& s) {
  core::write_file_atomically(path, surface_to_json(s).dump(2) + "\n");
}

}  // namespace fitlib::surface
