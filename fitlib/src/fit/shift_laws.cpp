// Given shift factors, the polynomial shift law and cards carrying a law fitted to shifts.
#include "fitlib/fit/shift_laws.hpp"

#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"

namespace fitlib::fit {
namespace {

std::string number(double v, const char* fmt = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

PolynomialShiftFit fit_polynomial_shift(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT,
                                        double reference_C, int degree) {
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

double given_log10_aT(const data::ShiftFactorTable& shifts, double temperature_C, double reference_C) {
  return data::interpolate_log10_aT(shifts, temperature_C) - data::interpolate_log10_aT(shifts, reference_C);
}

MasterCurve master_curve_from_shift_factors(const data::DynamicTestTable& raw, const data::ShiftFactorTable& shifts,
                                            double reference_C) {
  MasterCurveOptions options;
  options.reference_C = reference_C;
  MasterCurve curve = build_master_curve(raw, options);
  std::vector<double> log10_aT;
  for (auto& iso : curve.isotherms) {
    log10_aT.push_back(given_log10_aT(shifts, iso.temperature_C, reference_C));
    iso.pair_rms_decades = std::nan("");
    iso.pair_overlap_points = 0;
  }
  apply_shifts(curve, raw, log10_aT);
  curve.messages.push_back("shifts from " + shifts.source_file + " (interpolated at the isotherm temperatures)");
  return curve;
}

data::RelaxationTable shift_relaxation_table(const data::RelaxationTable& raw, const data::ShiftFactorTable& shifts,
                                             double reference_C) {
  data::RelaxationTable out = raw;
  for (auto& row : out.rows) {
    if (std::isnan(row.temperature_C))
      throw core::InputError("row without a temperature cannot be shifted", row.source_file, row.source_line);
    row.time_s /= std::pow(10.0, given_log10_aT(shifts, row.temperature_C, reference_C));
    row.temperature_C = reference_C;
  }
  return out;
}

FitResult with_law_from_shifts(const FitResult& result, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, const std::string& law,
                               int polynomial_degree) {
  std::vector<std::pair<std::string, double>> constants;
  std::string summary;
  double rms = 0.0;
  int degree_option = 0;
  if (law == "wlf") {
    const WlfFit w = fit_wlf(temperatures_C, log10_aT, reference_C);
    if (std::isnan(w.C1)) throw core::UsageError("shift law: no WLF fit (it needs at least 3 isotherms)");
    constants = {{"C1", w.C1}, {"C2", w.C2_K}};
    summary = "WLF C1 = " + number(w.C1) + ", C2 = " + number(w.C2_K) + " K";
    rms = w.rms_decades;
  } else if (law == "polynomial") {
    const PolynomialShiftFit poly = fit_polynomial_shift(temperatures_C, log10_aT, reference_C, polynomial_degree);
    summary = "polynomial";
    for (int k = 0; k < polynomial_degree; ++k) {
      constants.push_back({"poly_C" + std::to_string(k + 1), poly.coefficients[k]});
      summary += " C" + std::to_string(k + 1) + " = " + number(poly.coefficients[k]);
    }
    degree_option = polynomial_degree;
    rms = poly.rms_decades;
  } else {
    throw core::UsageError("shift law '" + law + "' cannot be fitted to shifts (wlf or polynomial)");
  }
  if (!result.model) throw core::UsageError("shift law: the fit result has no model");
  auto options = result.model->options();
  if (degree_option > 0) options["polynomial_degree"] = degree_option;
  options["temperature_law"] = law;
  options["reference_C"] = reference_C;
  FitResult out = result;
  out.model = model::make_model(result.model->kind(), options);
  out.values.clear();
  out.parameters.clear();
  for (const auto& spec : out.model->parameters()) {
    const int i = core::find_parameter(result.model->parameters(), spec.name);
    if (i >= 0) {
      out.values.push_back(result.values[i]);
      out.parameters.push_back(result.parameters[i]);
      continue;
    }
    ParameterResult p;
    p.name = spec.name;
    p.unit = spec.unit;
    p.fixed = true;
    bool found = false;
    for (const auto& [name, value] : constants)
      if (name == spec.name) p.value = value, found = true;
    if (!found) throw core::UsageError("shift law: parameter '" + spec.name + "' has no value");
    p.reason = "fitted to the isotherm shifts (" + law + " rms " + number(rms, "%.3g") + " decades)";
    out.values.push_back(p.value);
    out.parameters.push_back(p);
  }
  out.messages.push_back("master curve: " + summary + " at T_ref = " + number(reference_C) + " degC, fitted to " +
                         std::to_string(temperatures_C.size()) + " isotherm shifts");
  return out;
}

data::ShiftFactorTable shift_factors_of(const MasterCurve& curve) {
  data::ShiftFactorTable t;
  t.reference_C = curve.reference_C;
  for (const auto& iso : curve.isotherms) t.factors.push_back({iso.temperature_C, iso.log10_aT});
  return t;
}

}  // namespace fitlib::fit
