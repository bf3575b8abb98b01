#include "admissible.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "fitlib/core/units.hpp"

namespace fitlib::fit::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGasConstant_kJ_molK = 8.314462618e-3;

// ln a_T of the model's temperature law (its card form, Model::temperature_law) at T; false
// for a law not known here.
bool log_shift(const nlohmann::json& law, double temperature_C, double& ln_aT) {
  const std::string name = law.value("law", std::string("none"));
  ln_aT = 0.0;
  if (name == "none") return true;
  if (!std::isfinite(temperature_C)) return true;
  const double t_ref = law.value("reference_C", 23.0), dT = temperature_C - t_ref;
  if (name == "wlf") {
    const double c1 = law.value("C1", 0.0), c2 = law.value("C2_K", 0.0);
    if (!(c2 + dT > 0.0)) return false;
    ln_aT = -c1 * dT / (c2 + dT) * std::log(10.0);
    return true;
  }
  if (name == "arrhenius") {
    ln_aT = law.value("activation_energy_kJ_mol", 0.0) / kGasConstant_kJ_molK *
            (1.0 / core::kelvin_from_celsius(temperature_C) - 1.0 / core::kelvin_from_celsius(t_ref));
    return true;
  }
  return false;
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
  return s;
}

AdmissibleWindow admissible_window(const Problem& problem, const std::vector<double>& p) {
  AdmissibleWindow w;
  const SeriesTerms series = series_terms(problem.specs());
  if (series.empty()) return w;
  const nlohmann::json law = problem.model().temperature_law(p.data());
  const model::TestMode native = problem.model().native_mode();
  double omega_min = kInf, omega_max = 0.0, storage_min = kInf, storage_max = 0.0;
  for (const auto& row : problem.table().rows) {
    if (row.condition.mode == model::TestMode::bulk && native != model::TestMode::bulk) continue;
    double ln_aT = 0.0;
    if (!log_shift(law, row.condition.temperature_C, ln_aT)) return w;
    const double omega = core::angular_frequency(row.condition.frequency_Hz) * std::exp(ln_aT);
    omega_min = std::min(omega_min, omega);
    omega_max = std::max(omega_max, omega);
    storage_min = std::min(storage_min, row.storage_MPa);
    storage_max = std::max(storage_max, row.storage_MPa);
  }
  if (!(omega_min > 0.0) || !std::isfinite(omega_max)) return w;
  const FitOptions& o = problem.options();
  const double margin = std::pow(10.0, o.tau_margin_decades);
  w.applies = true;
  w.tau_min_s = 1.0 / (omega_max * margin);
  w.tau_max_s = margin / omega_min;
  const auto& specs = problem.specs();
  const bool moduli = std::all_of(series.moduli.begin(), series.moduli.end(),
                                  [&](int i) { return specs[i].linear; });
  if (moduli && o.modulus_ceiling > 0.0) w.modulus_max_MPa = o.modulus_ceiling * storage_max;
  if (series.relaxed >= 0 && specs[series.relaxed].linear && o.relaxed_floor > 0.0)
    w.relaxed_min_MPa = o.relaxed_floor * storage_min;
  return w;
}

int apply_admissible_bounds(Problem& problem, const AdmissibleWindow& w) {
  if (!w.applies) return 0;
  const SeriesTerms series = series_terms(problem.specs());
  int moved = 0;
  auto restrict = [&](int i, double lo, double hi) {
    if (problem.user_fixed()[i]) return;
    moved += problem.restrict_bounds(i, lo, hi) ? 1 : 0;
  };
  for (int i : series.times) restrict(i, w.tau_min_s, w.tau_max_s);
  if (w.modulus_max_MPa > 0.0)
    for (int i : series.moduli) restrict(i, 0.0, w.modulus_max_MPa);
  if (w.relaxed_min_MPa > 0.0) restrict(series.relaxed, w.relaxed_min_MPa, kInf);
  return moved;
}

}  // namespace fitlib::fit::detail
