// Joint refinement of a master curve: the model and every isotherm's shift fitted together on
// the raw rows (docs/fitting.md, "Master curves from raw isotherms").
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/time_series.hpp"
#include "isotherms.hpp"

namespace fitlib::fit {
namespace {

// The inner model at reduced frequency, one shift per isotherm keyed on the row's temperature.
class IsothermShiftModel : public model::Model {
 public:
  IsothermShiftModel(model::ModelPtr inner, std::vector<double> temperatures_C, double tolerance_C)
      : inner_(std::move(inner)), temperatures_(std::move(temperatures_C)), tolerance_C_(tolerance_C) {
    specs_ = inner_->parameters();
    n_inner_ = specs_.size();
    for (std::size_t k = 0; k < temperatures_.size(); ++k)
      specs_.push_back({"log_aT_" + std::to_string(k), "decades", -40.0, 40.0, core::Transform::linear, "shift", 0.0,
                        false});
  }

  std::string kind() const override { return "isotherm-shifts"; }
  const std::vector<core::ParameterSpec>& parameters() const override { return specs_; }
  nlohmann::json options() const override {
    return {{"inner_kind", inner_->kind()}, {"inner_options", inner_->options()},
            {"isotherm_temperatures_C", temperatures_}, {"tolerance_C", tolerance_C_}};
  }

  model::Moduli<double> moduli(const double* p, const model::TestCondition& c) const override {
    return inner_->moduli(p, reduced(p, c, 0.0));
  }

  model::Moduli<double> moduli(const double* p, const model::TestCondition& c,
                               Eigen::Ref<Eigen::MatrixXd> jacobian) const override {
    jacobian.setZero();
    const int k = isotherm(c);
    const auto value = inner_->moduli(p, reduced(p, c, 0.0), jacobian.leftCols(n_inner_));
    // d/d log a_T by central differences in log f (step 1e-4 decades: error ~1e-9 relative).
    constexpr double h = 1e-4;
    const auto up = inner_->moduli(p, reduced(p, c, h)), down = inner_->moduli(p, reduced(p, c, -h));
    jacobian(0, n_inner_ + k) = (up.storage - down.storage) / (2 * h);
    jacobian(1, n_inner_ + k) = (up.loss - down.loss) / (2 * h);
    jacobian(2, n_inner_ + k) = (up.mean - down.mean) / (2 * h);
    return value;
  }

  std::vector<double> stress_response(const double* p, const model::TestCondition& c,
                                      const model::StrainHistory& history) const override {
    model::StrainHistory h = history;  // reduced time t / a_T
    const double a_T = std::pow(10.0, p[n_inner_ + isotherm(c)]);
    for (auto& t : h.time_s) t /= a_T;
    return inner_->stress_response(p, reference(c), h);
  }
  double relaxation_modulus(const double* p, const model::TestCondition& c, double t_s) const override {
    return inner_->relaxation_modulus(p, reference(c), t_s / std::pow(10.0, p[n_inner_ + isotherm(c)]));
  }
  double creep_compliance(const double* p, const model::TestCondition& c, double t_s) const override {
    return inner_->creep_compliance(p, reference(c), t_s / std::pow(10.0, p[n_inner_ + isotherm(c)]));
  }
  model::TestMode native_mode() const override { return inner_->native_mode(); }
  bool maxwell_series(const double* p, model::MaxwellSeries* out) const override {
    return inner_->maxwell_series(p, out);  // at the reference temperature the shifts are 1
  }
  nlohmann::json temperature_law(const double* p) const override {
    std::vector<double> shifts(p + n_inner_, p + specs_.size());
    return {{"law", "tabulated"}, {"temperatures_C", temperatures_}, {"log10_aT", shifts}};
  }
  // The capabilities of the inner model at the reference temperature (the shifts are 1 there);
  // the law is the table of shifts (ShiftLaw::other), no point: a card's model gives that.
  bool kelvin_series(const double* p, model::KelvinSeries* out) const override { return inner_->kelvin_series(p, out); }
  double bulk_modulus(const double* p) const override { return inner_->bulk_modulus(p); }
  bool amplitude_dependent() const override { return inner_->amplitude_dependent(); }
  model::TemperatureLawInfo temperature_law_info() const override {
    model::TemperatureLawInfo info;
    info.law = model::ShiftLaw::other;
    info.reference_C = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < temperatures_.size(); ++k) info.shift_parameters.push_back(int(n_inner_ + k));
    return info;
  }
  model::TemperatureFactors temperature_factors(const double* p, double temperature_C) const override {
    model::TestCondition c;
    c.temperature_C = temperature_C;
    if (!c.has_temperature()) return {};
    return {std::pow(10.0, p[n_inner_ + isotherm(c)]), 1.0};
  }
  std::shared_ptr<const model::MaterialPoint> material_point(const double*, const model::PointOptions&) const override {
    throw core::UsageError("isotherm shifts are a fitter's internal model and have no material point");
  }
  std::vector<double> initial_parameters(const model::DataSummary& d) const override {
    auto p = inner_->initial_parameters(d);
    p.resize(specs_.size(), 0.0);
    return p;
  }

 private:
  int isotherm(const model::TestCondition& c) const {
    int best = -1;
    double dist = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < temperatures_.size(); ++k) {
      const double d = std::abs(c.temperature_C - temperatures_[k]);
      if (d < dist) dist = d, best = static_cast<int>(k);
    }
    if (!(dist <= tolerance_C_))
      throw core::InputError("isotherm shifts: temperature " + std::to_string(c.temperature_C) +
                             " degC is not within " + core::format_number(tolerance_C_) + " degC of an isotherm");
    return best;
  }
  model::TestCondition reference(const model::TestCondition& c) const {
    model::TestCondition r = c;
    r.temperature_C = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  model::TestCondition reduced(const double* p, const model::TestCondition& c, double extra_decades) const {
    model::TestCondition r = reference(c);
    r.frequency_Hz = c.frequency_Hz * std::pow(10.0, p[n_inner_ + isotherm(c)] + extra_decades);
    return r;
  }

  model::ModelPtr inner_;
  std::vector<double> temperatures_;
  double tolerance_C_;
  std::vector<core::ParameterSpec> specs_;
  Eigen::Index n_inner_ = 0;
};

// Half the smallest gap between isotherm temperatures: every raw row must land on its own
// isotherm (the key is the measured temperature).
double isotherm_tolerance(const std::vector<double>& temperatures) {
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < temperatures.size(); ++k) gap = std::min(gap, temperatures[k + 1] - temperatures[k]);
  return 0.5 * gap;
}

// The raw rows with each isotherm's vertical factor applied (held in the joint fit); InputError
// for a row nearer another isotherm.
data::DynamicTestTable rows_with_vertical_factors(const MasterCurve& curve, const data::DynamicTestTable& raw,
                                                  double tolerance) {
  data::DynamicTestTable rows = raw;
  for (const auto& iso : curve.isotherms) {
    for (int r : iso.rows) {
      auto& row = rows.rows[r];
      if (std::abs(row.condition.temperature_C - iso.temperature_C) >= tolerance)
        throw core::InputError("joint shift refinement: the row's temperature " +
                                   std::to_string(row.condition.temperature_C) + " degC is nearer another isotherm than " +
                                   iso.set + " (" + core::format_number(iso.temperature_C) + " degC)",
                               row.source_file, row.source_line);
      const double b_T = std::pow(10.0, iso.log10_bT);
      row.storage_MPa *= b_T;
      row.loss_MPa *= b_T;
    }
  }
  return rows;
}

}  // namespace

model::ModelPtr make_isotherm_shift_model(model::ModelPtr inner, std::vector<double> isotherm_temperatures_C,
                                          double tolerance_C) {
  return std::make_shared<IsothermShiftModel>(std::move(inner), std::move(isotherm_temperatures_C), tolerance_C);
}

MasterFit fit_master_curve(const model::ModelPtr& model, const data::DynamicTestTable& raw,
                           const MasterCurveOptions& curve_options, const FitOptions& fit_options,
                           bool refine_shifts) {
  MasterFit out;
  out.curve = build_master_curve(raw, curve_options);
  for (const auto& iso : out.curve.isotherms) out.pairwise_log10_aT.push_back(iso.log10_aT);
  out.master = fit(model, out.curve.master, fit_options);
  const int n = static_cast<int>(out.curve.isotherms.size());
  if (!refine_shifts || n < 2) return out;

  std::vector<double> temperatures;
  for (const auto& iso : out.curve.isotherms) temperatures.push_back(iso.temperature_C);
  const double tolerance = isotherm_tolerance(temperatures);
  const auto shifted = make_isotherm_shift_model(model, temperatures, tolerance);
  std::vector<double> start = out.master.values;
  start.insert(start.end(), out.pairwise_log10_aT.begin(), out.pairwise_log10_aT.end());
  const int anchor = detail::nearest_temperature(temperatures, out.curve.reference_C);
  FitOptions joint_options = fit_options;
  joint_options.fixed.push_back(shifted->parameters()[model->size() + anchor].name);
  out.joint = fit(shifted, rows_with_vertical_factors(out.curve, raw, tolerance), joint_options, &start);
  const auto& v = out.joint->values;
  apply_shifts(out.curve, raw, std::vector<double>(v.end() - n, v.end()));
  return out;
}

}  // namespace fitlib::fit
