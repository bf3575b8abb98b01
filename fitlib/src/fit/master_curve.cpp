// Master curves from raw isotherms: pairwise shifts chained from the anchor isotherm,
// re-referenced to T_ref, and the shifted master table (docs/fitting.md, "Master curves from raw
// isotherms").
#include "fitlib/fit/master_curve.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "isotherms.hpp"
#include "pair_shift.hpp"

namespace fitlib::fit {
namespace {

using detail::Isotherm;
using detail::PairShift;

// Linear interpolation (extrapolation at the ends) of y(T) at t.
double interpolate(const std::vector<double>& temperatures, const std::vector<double>& y, double t) {
  if (temperatures.size() == 1) return y.front();
  std::size_t hi = 1;
  while (hi + 1 < temperatures.size() && temperatures[hi] < t) ++hi;
  const std::size_t lo = hi - 1;
  return y[lo] + (y[hi] - y[lo]) * (t - temperatures[lo]) / (temperatures[hi] - temperatures[lo]);
}

// Fills each isotherm's series; an isotherm with a single frequency among several has no
// determined shift (InputError naming its first row).
void prepare_series(std::vector<Isotherm>& isotherms, const data::DynamicTestTable& raw, const MasterCurveOptions& o,
                    MasterCurve& curve) {
  const int n = static_cast<int>(isotherms.size());
  for (auto& iso : isotherms) {
    detail::fill_series(iso, raw, o, curve.reference_C);
    std::vector<double> distinct = iso.storage.x;
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (n > 1 && distinct.size() < 2) {
      const auto& row = raw.rows[iso.rows.front()];
      throw core::InputError("master curve: isotherm " + detail::set_label(iso) + " (" +
                                 core::format_number(iso.temperature_C) +
                                 " degC) has a single frequency: its shift is not determined",
                             row.source_file, row.source_line);
    }
    if (!iso.has_loss && o.loss_weight > 0)
      curve.messages.push_back("isotherm " + detail::set_label(iso) + " has a zero loss modulus: its pairs match E' only");
  }
}

// Pairwise shifts between neighbours chained from the anchor (a chain's least squares), then
// re-referenced so that log a_T(T_ref) = 0; log_b gets the fitted vertical offsets.
void chain_shifts(const std::vector<PairShift>& pairs, const std::vector<double>& temperatures, int anchor,
                  double reference_C, std::vector<double>& log_a, std::vector<double>& log_b) {
  const int n = static_cast<int>(temperatures.size());
  log_a.assign(n, 0.0);
  log_b.assign(n, 0.0);
  for (int k = anchor + 1; k < n; ++k) {
    log_a[k] = log_a[k - 1] + pairs[k - 1].shift;
    log_b[k] = log_b[k - 1] - pairs[k - 1].vertical;
  }
  for (int k = anchor - 1; k >= 0; --k) {
    log_a[k] = log_a[k + 1] - pairs[k].shift;
    log_b[k] = log_b[k + 1] + pairs[k].vertical;
  }
  const double at_reference = interpolate(temperatures, log_a, reference_C);
  for (auto& s : log_a) s -= at_reference;
}

// The isotherm's record with its pair figures against the colder neighbour, and the notes on
// pairs that rest on extrapolation or sit at the search bound.
IsothermShift shift_record(const Isotherm& iso, const PairShift* colder, double log_b, const MasterCurveOptions& o,
                           MasterCurve& curve) {
  IsothermShift s;
  s.set = detail::set_label(iso);
  s.temperature_C = iso.temperature_C;
  s.rows = iso.rows;
  s.log10_bT = o.vertical == VerticalShift::entropic
                   ? std::log10(core::kelvin_from_celsius(curve.reference_C) / core::kelvin_from_celsius(s.temperature_C))
                   : log_b;
  if (!colder) return s;
  s.pair_rms_decades = colder->rms;
  s.pair_overlap_points = colder->overlap;
  if (colder->overlap == 0)
    curve.messages.push_back("isotherms " + curve.isotherms.back().set + " and " + s.set +
                             " do not overlap at their shift: it rests on power-law extrapolation");
  if (o.monotone && colder->shift <= -o.max_pair_shift_decades + detail::kGridStep_decades)
    curve.messages.push_back("the shift between isotherms " + curve.isotherms.back().set + " and " + s.set +
                             " sits at the search bound (" + core::format_number(o.max_pair_shift_decades, 6) +
                             " decades)");
  return s;
}

}  // namespace

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
  auto isotherms = detail::group_isotherms(raw, o, curve.messages);
  const int n = static_cast<int>(isotherms.size());
  std::vector<double> temperatures;
  for (const auto& iso : isotherms) temperatures.push_back(iso.temperature_C);
  curve.reference_C = std::isnan(o.reference_C) ? isotherms[(n - 1) / 2].temperature_C : o.reference_C;
  const int anchor = detail::nearest_temperature(temperatures, curve.reference_C);
  prepare_series(isotherms, raw, o, curve);

  std::vector<PairShift> pairs(std::max(0, n - 1));
  for (int k = 0; k + 1 < n; ++k) pairs[k] = detail::best_pair_shift(isotherms[k], isotherms[k + 1], o);
  std::vector<double> log_a, log_b;
  chain_shifts(pairs, temperatures, anchor, curve.reference_C, log_a, log_b);
  for (int k = 0; k < n; ++k)
    curve.isotherms.push_back(shift_record(isotherms[k], k > 0 ? &pairs[k - 1] : nullptr, log_b[k], o, curve));
  apply_shifts(curve, raw, log_a);
  if (n == 1) curve.messages.push_back("a single isotherm: shift 0, no temperature law fitted");
  return curve;
}

MasterCurve build_relaxation_master_curve(const data::RelaxationTable& raw, MasterCurveOptions options) {
  data::DynamicTestTable proxy;
  proxy.source_files = raw.source_files;
  proxy.source_sha256 = raw.source_sha256;
  for (const data::RelaxationRow& r : raw.rows) {
    data::DynamicTestRow row;
    row.condition.mode = r.mode;
    row.condition.frequency_Hz = 1.0 / (2.0 * core::kPi * r.time_s);
    row.condition.temperature_C = r.temperature_C;
    row.storage_MPa = r.modulus_MPa;
    row.weight = r.weight;
    row.set = r.set;
    row.source_file = r.source_file;
    row.source_line = r.source_line;
    proxy.rows.push_back(row);
  }
  options.loss_weight = 0.0;  // a relaxation isotherm has one modulus
  MasterCurve curve = build_master_curve(proxy, options);
  curve.master = {};
  return curve;
}

}  // namespace fitlib::fit
