// Given shift factors, the polynomial shift law and cards carrying a law fitted to shifts.
#include "fitlib/fit/shift_laws.hpp"

#include <Eigen/QR>
#include <algorithm>
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

namespace {

// The law's constants fitted to the shifts, in the order of TemperatureLawInfo::shift_parameters.
struct LawConstants {
  std::vector<double> values;
  std::string summary;
  double rms_decades = 0.0;
};

LawConstants fit_law_constants(model::ShiftLaw law, const std::vector<double>& temperatures_C,
                               const std::vector<double>& log10_aT, double reference_C, int polynomial_degree) {
  LawConstants c;
  if (law == model::ShiftLaw::wlf) {
    const WlfFit w = fit_wlf(temperatures_C, log10_aT, reference_C);
    if (std::isnan(w.C1)) throw core::UsageError("shift law: no WLF fit (it needs at least 3 isotherms)");
    c.values = {w.C1, w.C2_K};
    c.summary = "WLF C1 = " + number(w.C1) + ", C2 = " + number(w.C2_K) + " K";
    c.rms_decades = w.rms_decades;
  } else if (law == model::ShiftLaw::polynomial) {
    const PolynomialShiftFit poly = fit_polynomial_shift(temperatures_C, log10_aT, reference_C, polynomial_degree);
    c.values = poly.coefficients;
    c.summary = "polynomial";
    for (int k = 0; k < polynomial_degree; ++k)
      c.summary += " C" + std::to_string(k + 1) + " = " + number(poly.coefficients[k]);
    c.rms_decades = poly.rms_decades;
  } else {
    throw core::UsageError("shift law '" + model::to_string(law) + "' cannot be fitted to shifts (wlf or polynomial)");
  }
  return c;
}

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
  const LawConstants constants = fit_law_constants(law, temperatures_C, log10_aT, reference_C, polynomial_degree);
  if (!result.model) throw core::UsageError("shift law: the fit result has no model");
  FitResult out = result;
  out.model = model_with_law(*result.model, law, reference_C, polynomial_degree);
  const model::TemperatureLawInfo info = out.model->temperature_law_info();
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
               number(constants.rms_decades, "%.3g") + " decades)";
    out.values.push_back(p.value);
    out.parameters.push_back(p);
  }
  out.messages.push_back("master curve: " + constants.summary + " at T_ref = " + number(reference_C) +
                         " degC, fitted to " + std::to_string(temperatures_C.size()) + " isotherm shifts");
  return out;
}

data::ShiftFactorTable shift_factors_of(const MasterCurve& curve) {
  data::ShiftFactorTable t;
  t.reference_C = curve.reference_C;
  for (const auto& iso : curve.isotherms) t.factors.push_back({iso.temperature_C, iso.log10_aT});
  return t;
}

}  // namespace fitlib::fit
