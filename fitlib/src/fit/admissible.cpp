#include "admissible.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fitlib/core/units.hpp"

namespace fitlib::fit::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// a_T of the model's temperature law at T (Model::temperature_factors); false for a law the
// window is not placed under (tabulated, a model's own) and at or beyond the WLF pole.
bool shift_factor(const model::Model& m, const std::vector<double>& p, double temperature_C, double& a_T) {
  const model::TemperatureLawInfo law = m.temperature_law_info();
  a_T = 1.0;
  if (law.law == model::ShiftLaw::other) return false;
  if (law.law == model::ShiftLaw::none || !std::isfinite(temperature_C)) return true;
  if (law.pole_parameter >= 0 && !(p[law.pole_parameter] + (temperature_C - law.reference_C) > 0.0)) return false;
  a_T = m.temperature_factors(p.data(), temperature_C).shift_factor;
  return true;
}

}  // namespace

SeriesTerms series_terms(const std::vector<core::ParameterSpec>& specs) {
  SeriesTerms s;
  for (int i = 0; i < static_cast<int>(specs.size()); ++i) {
    if (specs[i].group == "viscous") s.moduli.push_back(i);
    if (specs[i].group == "time") s.times.push_back(i);
    if (specs[i].group == "elastic" && s.relaxed < 0) s.relaxed = i;
  }
  if (s.moduli.size() != s.times.size()) return {};
  s.compliance = s.relaxed >= 0 && specs[s.relaxed].unit == "1/MPa";
  return s;
}

AdmissibleWindow admissible_window(const Problem& problem, const std::vector<double>& p) {
  AdmissibleWindow w;
  const SeriesTerms series = series_terms(problem.specs());
  if (series.empty()) return w;
  const model::TestMode native = problem.model().native_mode();
  double omega_min = kInf, omega_max = 0.0, storage_min = kInf, storage_max = 0.0;
  for (const auto& row : problem.table().rows) {
    if (row.condition.mode == model::TestMode::bulk && native != model::TestMode::bulk) continue;
    double a_T = 1.0;
    if (!shift_factor(problem.model(), p, row.condition.temperature_C, a_T)) return w;
    const double omega = core::angular_frequency(row.condition.frequency_Hz) * a_T;
    omega_min = std::min(omega_min, omega);
    omega_max = std::max(omega_max, omega);
    storage_min = std::min(storage_min, row.storage_MPa);
    storage_max = std::max(storage_max, row.storage_MPa);
  }
  if (!(omega_min > 0.0) || !std::isfinite(omega_max)) return w;
  return window_over(series, problem.specs(), problem.options(), omega_min, omega_max, storage_min, storage_max);
}

AdmissibleWindow window_over(const SeriesTerms& series, const std::vector<core::ParameterSpec>& specs,
                             const FitOptions& o, double omega_min, double omega_max, double storage_min,
                             double storage_max) {
  AdmissibleWindow w;
  const double margin = std::pow(10.0, o.tau_margin_decades);
  w.applies = true;
  w.tau_min_s = 1.0 / (omega_max * margin);
  w.tau_max_s = margin / omega_min;
  const bool moduli = std::all_of(series.moduli.begin(), series.moduli.end(),
                                  [&](int i) { return specs[i].linear; });
  if (moduli && o.modulus_ceiling > 0.0) w.modulus_max_MPa = o.modulus_ceiling * storage_max;
  if (series.relaxed >= 0 && specs[series.relaxed].linear && o.relaxed_floor > 0.0)
    w.relaxed_min_MPa = o.relaxed_floor * storage_min;
  // A retardation spectrum left free drove J_g to 1e-50 (1/J_g 1e50 MPa) on pyvisco's master curve.
  if (series.compliance && o.modulus_ceiling > 0.0) w.glassy_modulus_max_MPa = o.modulus_ceiling * storage_max;
  return w;
}

std::optional<std::pair<double, double>> window_limits(const SeriesTerms& series, const AdmissibleWindow& w, int i) {
  auto has = [](const std::vector<int>& v, int k) { return std::find(v.begin(), v.end(), k) != v.end(); };
  if (has(series.times, i)) return std::make_pair(w.tau_min_s, w.tau_max_s);
  if (has(series.moduli, i) && w.modulus_max_MPa > 0.0) return std::make_pair(0.0, w.modulus_max_MPa);
  if (i == series.relaxed && series.compliance && w.glassy_modulus_max_MPa > 0.0)
    return std::make_pair(1.0 / w.glassy_modulus_max_MPa, kInf);
  if (i == series.relaxed && w.relaxed_min_MPa > 0.0) return std::make_pair(w.relaxed_min_MPa, kInf);
  return std::nullopt;
}

int apply_admissible_bounds(Problem& problem, const AdmissibleWindow& w) {
  if (!w.applies) return 0;
  const SeriesTerms series = series_terms(problem.specs());
  int moved = 0;
  for (int i = 0; i < static_cast<int>(problem.specs().size()); ++i)
    if (const auto limits = window_limits(series, w, i); limits && !problem.user_fixed()[i])
      moved += problem.restrict_bounds(i, limits->first, limits->second) ? 1 : 0;
  return moved;
}

std::string describe_window(const AdmissibleWindow& w, int moved) {
  std::ostringstream s;
  s << "admissible terms: time constants in [" << w.tau_min_s << ", " << w.tau_max_s << "] s";
  if (w.modulus_max_MPa > 0.0) s << ", term moduli <= " << w.modulus_max_MPa << " MPa";
  if (w.relaxed_min_MPa > 0.0) s << ", relaxed modulus >= " << w.relaxed_min_MPa << " MPa";
  if (w.glassy_modulus_max_MPa > 0.0) s << ", instantaneous modulus 1/J_g <= " << w.glassy_modulus_max_MPa << " MPa";
  if (moved > 0) s << " (" << moved << " start values moved inside)";
  return s.str();
}

}  // namespace fitlib::fit::detail
