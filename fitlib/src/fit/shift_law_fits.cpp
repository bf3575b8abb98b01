// Temperature laws fitted to isotherm shifts: WLF, Arrhenius, pyvisco's polynomial, and cards
// that carry such a law (docs/fitting.md, "Master curves from raw isotherms" and "Shift-factor
// files and the polynomial law").
#include <Eigen/QR>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "law_constants.hpp"

namespace fitlib::fit {
namespace {

constexpr double kGasConstant_kJ_molK = 8.314462618e-3;
constexpr double kLn10 = 2.302585092994046;
constexpr int kBrentBits = 40;

// Temperatures and shifts pair up (a shorter log10_aT was read past its end).
void require_same_length(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT) {
  if (temperatures_C.size() != log10_aT.size())
    throw core::UsageError("shift law: " + std::to_string(temperatures_C.size()) + " temperatures but " +
                           std::to_string(log10_aT.size()) + " log10 a_T");
}

}  // namespace

WlfFit fit_wlf(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT, double reference_C,
               double C1_max, double C2_max_K) {
  require_same_length(temperatures_C, log10_aT);
  WlfFit fit;
  if (temperatures_C.size() < 3) return fit;
  // The free fit where it lies inside the bounds (the same search, the same numbers).
  if (std::isfinite(C1_max) || std::isfinite(C2_max_K)) {
    const WlfFit free = fit_wlf(temperatures_C, log10_aT, reference_C);
    if (free.C1 > 0.0 && free.C1 <= C1_max && free.C2_K <= C2_max_K) return free;
  }
  // Variable projection: for fixed C2 the law is linear in C1 (closed form; clamped to
  // [0, C1_max], which is the bounded optimum of a one-variable quadratic); C2 by Brent over
  // u = ln(C2 − C2_min), C2_min = max(T_ref − T) so that no data temperature reaches the pole.
  double c2_min = 0.0;
  for (double t : temperatures_C) c2_min = std::max(c2_min, reference_C - t);
  auto solve = [&](double u, double* c1_out) {
    const double c2 = c2_min + std::exp(u);
    double sgg = 0, sgs = 0;
    for (std::size_t k = 0; k < temperatures_C.size(); ++k) {
      const double dt = temperatures_C[k] - reference_C, g = -dt / (c2 + dt);
      sgg += g * g, sgs += g * log10_aT[k];
    }
    double c1 = sgg > 0 ? sgs / sgg : 0.0;
    if (std::isfinite(C1_max)) c1 = std::clamp(c1, std::numeric_limits<double>::min(), C1_max);
    double ss = 0;
    for (std::size_t k = 0; k < temperatures_C.size(); ++k) {
      const double dt = temperatures_C[k] - reference_C;
      ss += std::pow(log10_aT[k] + c1 * dt / (c2 + dt), 2);
    }
    if (c1_out) *c1_out = c1;
    return ss;
  };
  const double u_lo = std::log(1e-2), u_hi = std::max(u_lo, std::log(std::min(1e5, C2_max_K - c2_min)));
  double best_u = u_lo, best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 200; ++i) {
    const double u = u_lo + (u_hi - u_lo) * i / 200.0, ss = solve(u, nullptr);
    if (ss < best) best = ss, best_u = u;
  }
  const double step = (u_hi - u_lo) / 200.0;
  const auto [u, ss] = boost::math::tools::brent_find_minima([&](double v) { return solve(v, nullptr); },
                                                             std::max(u_lo, best_u - step),
                                                             std::min(u_hi, best_u + step), kBrentBits);
  const double u_best = ss <= best ? u : best_u;
  fit.rms_decades = std::sqrt(solve(u_best, &fit.C1) / temperatures_C.size());
  fit.C2_K = c2_min + std::exp(u_best);
  return fit;
}

ArrheniusFit fit_arrhenius(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT,
                           double reference_C) {
  require_same_length(temperatures_C, log10_aT);
  ArrheniusFit fit;
  if (temperatures_C.size() < 2) return fit;
  // Linear through the origin in h = (1/T − 1/T_ref) / (R ln 10).
  double shh = 0, shs = 0;
  std::vector<double> h(temperatures_C.size());
  for (std::size_t k = 0; k < h.size(); ++k) {
    h[k] = (1.0 / core::kelvin_from_celsius(temperatures_C[k]) - 1.0 / core::kelvin_from_celsius(reference_C)) /
           (kGasConstant_kJ_molK * kLn10);
    shh += h[k] * h[k], shs += h[k] * log10_aT[k];
  }
  fit.activation_energy_kJ_mol = shh > 0 ? shs / shh : 0.0;
  double ss = 0;
  for (std::size_t k = 0; k < h.size(); ++k) ss += std::pow(log10_aT[k] - fit.activation_energy_kJ_mol * h[k], 2);
  fit.rms_decades = std::sqrt(ss / h.size());
  return fit;
}

PolynomialShiftFit fit_polynomial_shift(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT,
                                        double reference_C, int degree) {
  require_same_length(temperatures_C, log10_aT);
  const int m = static_cast<int>(temperatures_C.size());
  if (degree < 1 || m < degree)
    throw core::UsageError("polynomial shift law: degree " + std::to_string(degree) + " needs at least as many shifts (" +
                           std::to_string(m) + ")");
  // Columns (ΔT/s)^k with s = the largest |ΔT| keep the normal matrix well scaled.
  double s = 1.0;
  for (double t : temperatures_C) s = std::max(s, std::abs(t - reference_C));
  Eigen::MatrixXd a(m, degree);
  Eigen::VectorXd b(m);
  for (int i = 0; i < m; ++i) {
    const double x = (temperatures_C[i] - reference_C) / s;
    for (int k = 0; k < degree; ++k) a(i, k) = std::pow(x, k + 1);
    b[i] = log10_aT[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  PolynomialShiftFit fit;
  for (int k = 0; k < degree; ++k) fit.coefficients.push_back(c[k] / std::pow(s, k + 1));
  fit.rms_decades = std::sqrt((a * c - b).squaredNorm() / m);
  return fit;
}

namespace detail {

LawConstants fit_law_constants(model::ShiftLaw law, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, int polynomial_degree,
                               const std::vector<core::ParameterSpec>& bounds) {
  LawConstants c;
  const auto upper = [&](std::size_t k) {
    return k < bounds.size() ? bounds[k].upper : std::numeric_limits<double>::infinity();
  };
  if (law == model::ShiftLaw::wlf) {
    const WlfFit w = fit_wlf(temperatures_C, log10_aT, reference_C, upper(0), upper(1));
    if (std::isnan(w.C1)) throw core::UsageError("shift law: no WLF fit (it needs at least 3 isotherms)");
    c.values = {w.C1, w.C2_K};
    for (std::size_t k = 0; k < 2; ++k)
      if (std::isfinite(upper(k)) && c.values[k] >= upper(k) * (1.0 - 1e-12))
        c.held_at_bound.push_back(bounds[k].name + " at its bound " + core::format_number(upper(k), 6) +
                                  " (the unbounded fit lies beyond)");
    c.summary = "WLF C1 = " + core::format_number(w.C1, 6) + ", C2 = " + core::format_number(w.C2_K, 6) + " K";
    c.rms_decades = w.rms_decades;
  } else if (law == model::ShiftLaw::polynomial) {
    const PolynomialShiftFit poly = fit_polynomial_shift(temperatures_C, log10_aT, reference_C, polynomial_degree);
    c.values = poly.coefficients;
    c.summary = "polynomial";
    for (int k = 0; k < polynomial_degree; ++k)
      c.summary += " C" + std::to_string(k + 1) + " = " + core::format_number(poly.coefficients[k], 6);
    c.rms_decades = poly.rms_decades;
  } else if (law == model::ShiftLaw::arrhenius) {
    const ArrheniusFit a = fit_arrhenius(temperatures_C, log10_aT, reference_C);
    if (std::isnan(a.activation_energy_kJ_mol))
      throw core::UsageError("shift law: no Arrhenius fit (it needs at least 2 isotherms)");
    c.values = {a.activation_energy_kJ_mol};
    c.summary = "Arrhenius E_a = " + core::format_number(a.activation_energy_kJ_mol, 6) + " kJ/mol";
    c.rms_decades = a.rms_decades;
  } else {
    throw core::UsageError("shift law '" + model::to_string(law) +
                           "' cannot be fitted to shifts (wlf, arrhenius or polynomial)");
  }
  // Arrhenius and the polynomial are linear in their constants: clamped one by one, a constant
  // past its bound is held there (the card would refuse it). WLF is bounded inside its fit.
  for (std::size_t k = 0; k < c.values.size() && k < bounds.size(); ++k) {
    const double lower = bounds[k].transform == core::Transform::log ? std::max(bounds[k].lower, std::numeric_limits<double>::min())
                                                                     : bounds[k].lower;
    const double held = std::clamp(c.values[k], lower, bounds[k].upper);
    if (held != c.values[k]) c.held_at_bound.push_back(bounds[k].name + " " + core::format_number(c.values[k], 6) + " held at " + core::format_number(held, 6));
    c.values[k] = held;
  }
  return c;
}

}  // namespace detail

namespace {

// The model of `result` with the law in its options (model.hpp: make_model rebuilds a model from them).
model::ModelPtr model_with_law(const model::Model& m, model::ShiftLaw law, double reference_C, int polynomial_degree) {
  auto options = m.options();
  if (law == model::ShiftLaw::polynomial) options["polynomial_degree"] = polynomial_degree;
  options["temperature_law"] = model::to_string(law);
  options["reference_C"] = reference_C;
  return model::make_model(m.kind(), options);
}

}  // namespace

FitResult with_law_from_shifts(const FitResult& result, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, model::ShiftLaw law,
                               int polynomial_degree) {
  if (!result.model) throw core::UsageError("shift law: the fit result has no model");
  FitResult out = result;
  out.model = model_with_law(*result.model, law, reference_C, polynomial_degree);
  const model::TemperatureLawInfo info = out.model->temperature_law_info();
  std::vector<core::ParameterSpec> bounds;  // the card reads back only constants inside these
  for (int i : info.shift_parameters) bounds.push_back(out.model->parameters()[i]);
  const detail::LawConstants constants =
      detail::fit_law_constants(law, temperatures_C, log10_aT, reference_C, polynomial_degree, bounds);
  if (info.law != law || info.shift_parameters.size() != constants.values.size())
    throw core::UsageError("shift law: model '" + out.model->kind() + "' does not carry a " + model::to_string(law) +
                           " law");
  out.values.clear();
  out.parameters.clear();
  const auto& specs = out.model->parameters();
  for (int j = 0; j < static_cast<int>(specs.size()); ++j) {
    const auto& spec = specs[j];
    const auto law_slot = std::find(info.shift_parameters.begin(), info.shift_parameters.end(), j);
    if (law_slot == info.shift_parameters.end()) {
      // The same parameter of the model fitted without the law.
      const int i = core::find_parameter(result.model->parameters(), spec.name);
      if (i < 0) throw core::UsageError("shift law: parameter '" + spec.name + "' has no value");
      out.values.push_back(result.values[i]);
      out.parameters.push_back(result.parameters[i]);
      continue;
    }
    ParameterResult p;
    p.name = spec.name;
    p.unit = spec.unit;
    p.fixed = true;
    p.value = constants.values[law_slot - info.shift_parameters.begin()];
    p.reason = "fitted to the isotherm shifts (" + model::to_string(law) + " rms " +
               core::format_number(constants.rms_decades, 3) + " decades)";
    out.values.push_back(p.value);
    out.parameters.push_back(p);
  }
  // A law that misses the shifts moves every other temperature's moduli along the frequency axis
  // by that much (docs/fitting.md, "Quality verdict"): a warning, not a note.
  if (constants.rms_decades > kShiftLawWarnDecades)
    out.quality.warnings.push_back("the " + model::to_string(law) + " law misses the isotherm shifts by " +
                                   core::format_number(constants.rms_decades, 3) + " decades rms (threshold " +
                                   core::format_number(kShiftLawWarnDecades, 3) +
                                   "): away from the reference temperature the card's moduli are shifted by as "
                                   "much; " +
                                   (law == model::ShiftLaw::polynomial
                                        ? std::string("a higher --polynomial-degree may follow them")
                                        : std::string("another --temperature-law (polynomial) may follow them")));
  out.messages.push_back("master curve: " + constants.summary + " at T_ref = " + core::format_number(reference_C, 6) +
                         " degC, fitted to " + std::to_string(temperatures_C.size()) + " isotherm shifts");
  for (const std::string& held : constants.held_at_bound)
    out.messages.push_back("master curve: " + held + ": the law is the best fit inside the bounds the card admits");
  return out;
}

FitResult with_wlf_from_shifts(const FitResult& result, const MasterCurve& curve) {
  std::vector<double> temperatures, log10_aT;
  for (const auto& iso : curve.isotherms) {
    temperatures.push_back(iso.temperature_C);
    log10_aT.push_back(iso.log10_aT);
  }
  return with_law_from_shifts(result, temperatures, log10_aT, curve.reference_C, model::ShiftLaw::wlf);
}

}  // namespace fitlib::fit
