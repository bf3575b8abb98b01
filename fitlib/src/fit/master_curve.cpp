// Master curves from raw isotherms: pairwise shifts, law fits, joint refinement with a model.
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/shift_laws.hpp"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::fit {
namespace {

constexpr double kGasConstant_kJ_molK = 8.314462618e-3;
constexpr double kLn10 = 2.302585092994046;
constexpr double kGridStep_decades = 0.05;  // pair-shift scan before Brent
constexpr int kBrentBits = 40;

// One modulus of an isotherm against log10 f: linear interpolation inside, a local power law
// (log-log line through the end point, slope by least squares over the end points) outside.
struct Series {
  std::vector<double> x, y;
  double slope_low = 0.0, slope_high = 0.0;

  void finish(int end_points) {
    const int n = static_cast<int>(x.size());
    const int m = std::min(std::max(end_points, 2), n);
    slope_low = slope(0, m);
    slope_high = slope(n - m, m);
  }
  double slope(int first, int count) const {
    double mx = 0, my = 0;
    for (int i = first; i < first + count; ++i) mx += x[i], my += y[i];
    mx /= count, my /= count;
    double sxx = 0, sxy = 0;
    for (int i = first; i < first + count; ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
    return sxx > 0 ? sxy / sxx : 0.0;
  }
  double value(double xq) const {
    if (xq <= x.front()) return y.front() + slope_low * (xq - x.front());
    if (xq >= x.back()) return y.back() + slope_high * (xq - x.back());
    const auto hi = std::upper_bound(x.begin(), x.end(), xq) - x.begin();
    const auto lo = hi - 1;
    const double span = x[hi] - x[lo];
    return span > 0 ? y[lo] + (y[hi] - y[lo]) * (xq - x[lo]) / span : 0.5 * (y[lo] + y[hi]);
  }
  double outside(double xq) const { return std::max({0.0, x.front() - xq, xq - x.back()}); }
};

struct Isotherm {
  std::vector<std::string> sets;
  double temperature_C = 0.0;
  std::vector<int> rows;
  Series storage, loss;  // log10 moduli (times the entropic factor when chosen)
  bool has_loss = true;
};

struct PairShift {
  double shift = 0.0, vertical = 0.0, rms = 0.0;
  int overlap = 0;
};

// Weighted mismatch of warm isotherm b shifted by d decades against cold isotherm a (in a's raw
// log f: x_b + d), both ways; with a fitted vertical offset the weighted mean is removed.
PairShift pair_mismatch(const Isotherm& a, const Isotherm& b, double d, const MasterCurveOptions& o) {
  double sw = 0, swr = 0, swrr = 0;
  int overlap = 0;
  const bool loss = a.has_loss && b.has_loss && o.loss_weight > 0;
  auto add = [&](double r, double w) { sw += w, swr += w * r, swrr += w * r * r; };
  auto compare = [&](const Isotherm& from, const Isotherm& to, double offset, double sign) {
    for (std::size_t j = 0; j < from.storage.x.size(); ++j) {
      const double xq = from.storage.x[j] + offset;
      const double dist = to.storage.outside(xq);
      if (dist == 0.0) ++overlap;
      const double w = std::exp(-dist / o.taper_decades);
      add(sign * (from.storage.y[j] - to.storage.value(xq)), w);
      if (loss) add(sign * (from.loss.y[j] - to.loss.value(xq)), w * o.loss_weight);
    }
  };
  compare(b, a, d, 1.0);    // residual = b − a
  compare(a, b, -d, -1.0);  // residual = b − a as well
  PairShift p;
  p.shift = d;
  p.overlap = overlap;
  p.vertical = o.vertical == VerticalShift::fitted ? swr / sw : 0.0;
  p.rms = std::sqrt(std::max(0.0, swrr / sw - (o.vertical == VerticalShift::fitted ? p.vertical * p.vertical : 0.0)));
  return p;
}

// Grid scan over the bracket, then Brent's method in the best grid cell.
PairShift best_pair_shift(const Isotherm& a, const Isotherm& b, const MasterCurveOptions& o) {
  const double lo = -o.max_pair_shift_decades, hi = o.monotone ? 0.0 : o.max_pair_shift_decades;
  double best_d = hi, best = std::numeric_limits<double>::infinity();
  const int steps = static_cast<int>(std::ceil((hi - lo) / kGridStep_decades));
  for (int i = 0; i <= steps; ++i) {
    const double d = std::min(hi, lo + i * kGridStep_decades);
    const double r = pair_mismatch(a, b, d, o).rms;
    if (r < best) best = r, best_d = d;
  }
  const auto objective = [&](double d) { return pair_mismatch(a, b, d, o).rms; };
  const auto [d, r] = boost::math::tools::brent_find_minima(
      objective, std::max(lo, best_d - kGridStep_decades), std::min(hi, best_d + kGridStep_decades), kBrentBits);
  return pair_mismatch(a, b, r <= best ? d : best_d, o);
}

std::string set_label(const Isotherm& iso) {
  std::string s;
  for (const auto& x : iso.sets) s += (s.empty() ? "" : "+") + x;
  return s;
}

// Rows → isotherms sorted by temperature; duplicates (by same_temperature_C) merged.
std::vector<Isotherm> group_isotherms(const data::DynamicTestTable& raw, const MasterCurveOptions& o,
                                      std::vector<std::string>& messages) {
  if (raw.rows.empty()) throw core::UsageError("master curve: the table has no rows");
  bool any_set = false;
  for (std::size_t i = 0; i < raw.rows.size(); ++i) {
    const auto& row = raw.rows[i];
    if (!row.condition.has_temperature())
      throw core::InputError("master curve: the row has no temperature (isotherms need temperature_C)",
                             row.source_file, row.source_line);
    any_set = any_set || !row.set.empty();
  }
  std::vector<Isotherm> groups;
  if (any_set) {
    std::map<std::string, int> index;
    for (std::size_t i = 0; i < raw.rows.size(); ++i) {
      auto [it, added] = index.emplace(raw.rows[i].set, static_cast<int>(groups.size()));
      if (added) {
        groups.emplace_back();
        groups.back().sets = {raw.rows[i].set};
      }
      groups[it->second].rows.push_back(static_cast<int>(i));
    }
    for (auto& g : groups) {
      double sum = 0;
      for (int r : g.rows) sum += raw.rows[r].condition.temperature_C;
      g.temperature_C = sum / g.rows.size();
    }
  } else {  // one group per cluster of temperatures
    std::vector<int> order(raw.rows.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return raw.rows[a].condition.temperature_C < raw.rows[b].condition.temperature_C;
    });
    double last = -std::numeric_limits<double>::infinity();
    for (int r : order) {
      const double t = raw.rows[r].condition.temperature_C;
      if (t - last >= o.same_temperature_C) groups.push_back({});
      groups.back().rows.push_back(r);
      last = t;
    }
    for (auto& g : groups) {
      double sum = 0;
      for (int r : g.rows) sum += raw.rows[r].condition.temperature_C;
      g.temperature_C = sum / g.rows.size();
      char label[32];
      std::snprintf(label, sizeof label, "%.4g C", g.temperature_C);
      g.sets = {label};
    }
  }
  std::stable_sort(groups.begin(), groups.end(),
                   [](const Isotherm& a, const Isotherm& b) { return a.temperature_C < b.temperature_C; });
  std::vector<Isotherm> merged;
  for (auto& g : groups) {
    if (!merged.empty() && g.temperature_C - merged.back().temperature_C < o.same_temperature_C) {
      auto& m = merged.back();
      messages.push_back("sets " + set_label(m) + " and " + set_label(g) + " have the same temperature (" +
                         std::to_string(m.temperature_C) + " / " + std::to_string(g.temperature_C) +
                         " degC): merged into one isotherm");
      const double n1 = m.rows.size(), n2 = g.rows.size();
      m.temperature_C = (n1 * m.temperature_C + n2 * g.temperature_C) / (n1 + n2);
      m.rows.insert(m.rows.end(), g.rows.begin(), g.rows.end());
      m.sets.insert(m.sets.end(), g.sets.begin(), g.sets.end());
    } else {
      merged.push_back(std::move(g));
    }
  }
  return merged;
}

void fill_series(Isotherm& iso, const data::DynamicTestTable& raw, const MasterCurveOptions& o, double reference_C) {
  auto rows = iso.rows;
  std::stable_sort(rows.begin(), rows.end(), [&](int a, int b) {
    return raw.rows[a].condition.frequency_Hz < raw.rows[b].condition.frequency_Hz;
  });
  const double log_b = o.vertical == VerticalShift::entropic
                           ? std::log10(core::kelvin_from_celsius(reference_C) / core::kelvin_from_celsius(iso.temperature_C))
                           : 0.0;
  for (int r : rows) {
    const auto& row = raw.rows[r];
    const double x = std::log10(row.condition.frequency_Hz);
    iso.storage.x.push_back(x);
    iso.storage.y.push_back(std::log10(row.storage_MPa) + log_b);
    iso.loss.x.push_back(x);
    iso.has_loss = iso.has_loss && row.loss_MPa > 0;
    iso.loss.y.push_back(row.loss_MPa > 0 ? std::log10(row.loss_MPa) + log_b : 0.0);
  }
  iso.storage.finish(o.extrapolation_points);
  iso.loss.finish(o.extrapolation_points);
}

// Linear interpolation (extrapolation at the ends) of y(T) at t.
double interpolate(const std::vector<double>& temperatures, const std::vector<double>& y, double t) {
  if (temperatures.size() == 1) return y.front();
  std::size_t hi = 1;
  while (hi + 1 < temperatures.size() && temperatures[hi] < t) ++hi;
  const std::size_t lo = hi - 1;
  return y[lo] + (y[hi] - y[lo]) * (t - temperatures[lo]) / (temperatures[hi] - temperatures[lo]);
}

std::string format_number(double v, const char* fmt = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// ---------------------------------------------------------------------------------------------
// Joint refinement: the inner model at reduced frequency, one shift per isotherm keyed on the
// row's temperature.
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
                             " degC is not within " + std::to_string(tolerance_C_) + " degC of an isotherm");
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

}  // namespace

WlfFit fit_wlf(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT, double reference_C) {
  WlfFit fit;
  if (temperatures_C.size() < 3) return fit;
  // Variable projection: for fixed C2 the law is linear in C1 (closed form); C2 by Brent over
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
    const double c1 = sgg > 0 ? sgs / sgg : 0.0;
    double ss = 0;
    for (std::size_t k = 0; k < temperatures_C.size(); ++k) {
      const double dt = temperatures_C[k] - reference_C;
      ss += std::pow(log10_aT[k] + c1 * dt / (c2 + dt), 2);
    }
    if (c1_out) *c1_out = c1;
    return ss;
  };
  const double u_lo = std::log(1e-2), u_hi = std::log(1e5);
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

void apply_shifts(MasterCurve& curve, const data::DynamicTestTable& raw, const std::vector<double>& log10_aT) {
  if (log10_aT.size() != curve.isotherms.size())
    throw core::UsageError("apply_shifts: " + std::to_string(log10_aT.size()) + " shifts for " +
                           std::to_string(curve.isotherms.size()) + " isotherms");
  data::DynamicTestTable master;
  master.source_files = raw.source_files;
  master.source_sha256 = raw.source_sha256;
  master.warnings = raw.warnings;
  std::vector<double> temperatures;
  for (std::size_t k = 0; k < curve.isotherms.size(); ++k) {
    auto& iso = curve.isotherms[k];
    iso.log10_aT = log10_aT[k];
    temperatures.push_back(iso.temperature_C);
    const double a_T = std::pow(10.0, iso.log10_aT), b_T = std::pow(10.0, iso.log10_bT);
    for (int r : iso.rows) {
      auto row = raw.rows[r];
      row.condition.frequency_Hz *= a_T;
      row.condition.temperature_C = curve.reference_C;
      row.storage_MPa *= b_T;
      row.loss_MPa *= b_T;
      master.rows.push_back(std::move(row));
    }
  }
  std::stable_sort(master.rows.begin(), master.rows.end(), [](const auto& a, const auto& b) {
    return a.condition.frequency_Hz < b.condition.frequency_Hz;
  });
  curve.master = std::move(master);
  curve.wlf = fit_wlf(temperatures, log10_aT, curve.reference_C);
  curve.arrhenius = fit_arrhenius(temperatures, log10_aT, curve.reference_C);
}

MasterCurve build_master_curve(const data::DynamicTestTable& raw, const MasterCurveOptions& o) {
  if (!(o.max_pair_shift_decades > 0) || o.loss_weight < 0 || o.extrapolation_points < 2 || !(o.taper_decades > 0))
    throw core::UsageError("master curve: max_pair_shift_decades > 0, loss_weight >= 0, taper_decades > 0 and "
                           "extrapolation_points >= 2 are required");
  MasterCurve curve;
  auto isotherms = group_isotherms(raw, o, curve.messages);
  const int n = static_cast<int>(isotherms.size());
  curve.reference_C = std::isnan(o.reference_C) ? isotherms[(n - 1) / 2].temperature_C : o.reference_C;
  int anchor = 0;
  for (int k = 1; k < n; ++k)
    if (std::abs(isotherms[k].temperature_C - curve.reference_C) <
        std::abs(isotherms[anchor].temperature_C - curve.reference_C))
      anchor = k;
  for (auto& iso : isotherms) {
    fill_series(iso, raw, o, curve.reference_C);
    std::vector<double> distinct = iso.storage.x;
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (n > 1 && distinct.size() < 2) {
      const auto& row = raw.rows[iso.rows.front()];
      throw core::InputError("master curve: isotherm " + set_label(iso) + " (" + std::to_string(iso.temperature_C) +
                                 " degC) has a single frequency: its shift is not determined",
                             row.source_file, row.source_line);
    }
    if (!iso.has_loss && o.loss_weight > 0)
      curve.messages.push_back("isotherm " + set_label(iso) + " has a zero loss modulus: its pairs match E' only");
  }

  // Pairwise shifts between neighbours, chained from the anchor (a chain's least squares).
  std::vector<PairShift> pairs(std::max(0, n - 1));
  for (int k = 0; k + 1 < n; ++k) pairs[k] = best_pair_shift(isotherms[k], isotherms[k + 1], o);
  std::vector<double> log_a(n, 0.0), log_b(n, 0.0);
  for (int k = anchor + 1; k < n; ++k) {
    log_a[k] = log_a[k - 1] + pairs[k - 1].shift;
    log_b[k] = log_b[k - 1] - pairs[k - 1].vertical;
  }
  for (int k = anchor - 1; k >= 0; --k) {
    log_a[k] = log_a[k + 1] - pairs[k].shift;
    log_b[k] = log_b[k + 1] + pairs[k].vertical;
  }
  std::vector<double> temperatures;
  for (const auto& iso : isotherms) temperatures.push_back(iso.temperature_C);
  const double at_reference = interpolate(temperatures, log_a, curve.reference_C);
  for (auto& s : log_a) s -= at_reference;

  for (int k = 0; k < n; ++k) {
    IsothermShift s;
    s.set = set_label(isotherms[k]);
    s.temperature_C = isotherms[k].temperature_C;
    s.rows = isotherms[k].rows;
    s.log10_bT = o.vertical == VerticalShift::entropic
                     ? std::log10(core::kelvin_from_celsius(curve.reference_C) /
                                  core::kelvin_from_celsius(s.temperature_C))
                     : log_b[k];
    if (k > 0) {
      s.pair_rms_decades = pairs[k - 1].rms;
      s.pair_overlap_points = pairs[k - 1].overlap;
      if (pairs[k - 1].overlap == 0)
        curve.messages.push_back("isotherms " + curve.isotherms.back().set + " and " + s.set +
                                 " do not overlap at their shift: it rests on power-law extrapolation");
      if (o.monotone && pairs[k - 1].shift <= -o.max_pair_shift_decades + kGridStep_decades)
        curve.messages.push_back("the shift between isotherms " + curve.isotherms.back().set + " and " + s.set +
                                 " sits at the search bound (" + format_number(o.max_pair_shift_decades) +
                                 " decades)");
    }
    curve.isotherms.push_back(std::move(s));
  }
  apply_shifts(curve, raw, log_a);
  if (n == 1) curve.messages.push_back("a single isotherm: shift 0, no temperature law fitted");
  return curve;
}

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

  // Tolerance: half the smallest gap between isotherm temperatures, and every raw row must land
  // on its own isotherm (the key is the measured temperature).
  std::vector<double> temperatures;
  for (const auto& iso : out.curve.isotherms) temperatures.push_back(iso.temperature_C);
  double gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < n; ++k) gap = std::min(gap, temperatures[k + 1] - temperatures[k]);
  const double tolerance = 0.5 * gap;
  data::DynamicTestTable rows = raw;  // vertical factors held
  for (int k = 0; k < n; ++k) {
    const auto& iso = out.curve.isotherms[k];
    for (int r : iso.rows) {
      auto& row = rows.rows[r];
      if (std::abs(row.condition.temperature_C - iso.temperature_C) >= tolerance)
        throw core::InputError("joint shift refinement: the row's temperature " +
                                   std::to_string(row.condition.temperature_C) + " degC is nearer another isotherm than " +
                                   iso.set + " (" + std::to_string(iso.temperature_C) + " degC)",
                               row.source_file, row.source_line);
      const double b_T = std::pow(10.0, iso.log10_bT);
      row.storage_MPa *= b_T;
      row.loss_MPa *= b_T;
    }
  }
  const auto shifted = make_isotherm_shift_model(model, temperatures, tolerance);
  std::vector<double> start = out.master.values;
  start.insert(start.end(), out.pairwise_log10_aT.begin(), out.pairwise_log10_aT.end());
  int anchor = 0;
  for (int k = 1; k < n; ++k)
    if (std::abs(temperatures[k] - out.curve.reference_C) < std::abs(temperatures[anchor] - out.curve.reference_C))
      anchor = k;
  FitOptions joint_options = fit_options;
  joint_options.fixed.push_back("log_aT_" + std::to_string(anchor));
  out.joint = fit(shifted, rows, joint_options, &start);
  const auto& v = out.joint->values;
  apply_shifts(out.curve, raw, std::vector<double>(v.end() - n, v.end()));
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

std::string format_shift_table(const MasterCurve& curve) {
  std::ostringstream s;
  s << "master curve: " << curve.isotherms.size() << " isotherms, T_ref = " << format_number(curve.reference_C)
    << " degC\n";
  s << "      T_C   log10_aT   log10_bT   pair_rms  overlap  set\n";
  for (const auto& iso : curve.isotherms) {
    char line[160];
    std::snprintf(line, sizeof line, "%9.3f %10.4f %10.4f %10.4f %8d  %s\n", iso.temperature_C, iso.log10_aT,
                  iso.log10_bT, iso.pair_rms_decades, iso.pair_overlap_points, iso.set.c_str());
    s << line;
  }
  s << "WLF: C1 = " << format_number(curve.wlf.C1) << ", C2 = " << format_number(curve.wlf.C2_K)
    << " K, rms " << format_number(curve.wlf.rms_decades, "%.3g") << " decades\n";
  s << "Arrhenius: E_a = " << format_number(curve.arrhenius.activation_energy_kJ_mol) << " kJ/mol, rms "
    << format_number(curve.arrhenius.rms_decades, "%.3g") << " decades\n";
  for (const auto& m : curve.messages) s << "note: " << m << "\n";
  return s.str();
}

std::string shift_table_csv(const MasterCurve& curve) {
  std::ostringstream s;
  s << "# fitlib master curve shifts, T_ref = " << format_number(curve.reference_C, "%.17g") << " degC\n";
  s << "# WLF C1 = " << format_number(curve.wlf.C1, "%.17g") << ", C2_K = " << format_number(curve.wlf.C2_K, "%.17g")
    << ", rms_decades = " << format_number(curve.wlf.rms_decades, "%.6g") << "\n";
  s << "# Arrhenius E_a_kJ_mol = " << format_number(curve.arrhenius.activation_energy_kJ_mol, "%.17g")
    << ", rms_decades = " << format_number(curve.arrhenius.rms_decades, "%.6g") << "\n";
  s << "T_C,log10_aT,log10_bT,set\n";
  for (const auto& iso : curve.isotherms) {
    std::string set = iso.set;
    if (set.find_first_of(",\"") != std::string::npos) {
      std::string q = "\"";
      for (char c : set) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      set = q + "\"";
    }
    s << format_number(iso.temperature_C, "%.17g") << "," << format_number(iso.log10_aT, "%.17g") << ","
      << format_number(iso.log10_bT, "%.17g") << "," << set << "\n";
  }
  return s.str();
}

}  // namespace fitlib::fit
