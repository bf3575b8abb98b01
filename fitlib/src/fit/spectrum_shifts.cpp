// Isotherm shifts refined with the smooth spectrum (docs/fitting.md "Master curves from raw
// isotherms", step 5 with the spectrum): block coordinate descent on the joint problem.
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <sstream>

#include "fitlib/core/timer.hpp"
#include "fitlib/fit/problem.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "isotherms.hpp"

namespace fitlib::fit {
namespace {

constexpr int kBrentBits = 30;

// The cost of one isotherm's rows at shift log10_aT under the fitted model (law none, at T_ref).
double isotherm_cost(const FitResult& card, const data::DynamicTestTable& raw, const IsothermShift& iso,
                     double reference_C, double log10_aT, const FitOptions& options) {
  data::DynamicTestTable t;
  const double a_T = std::pow(10.0, log10_aT), b_T = std::pow(10.0, iso.log10_bT);
  for (int r : iso.rows) {
    auto row = raw.rows[r];
    row.condition.frequency_Hz *= a_T;
    row.condition.temperature_C = reference_C;
    row.storage_MPa *= b_T;
    row.loss_MPa *= b_T;
    t.rows.push_back(row);
  }
  const Problem p(card.model, t, options, card.values);
  return p.cost(card.values);
}

// E′ only: the shifts follow the storage modulus, as the pairwise shifts do (MasterCurveOptions::
// loss_weight = 0; docs/fitting.md "Why E′ only by default").
FitOptions storage_only(FitOptions o) {
  o.loss_weight = 0.0;
  return o;
}

double storage_cost(const FitResult& card, const data::DynamicTestTable& master, const FitOptions& options) {
  const Problem p(card.model, master, storage_only(options), card.values);
  return p.cost(card.values);
}

}  // namespace

SpectrumMasterFit refine_shifts_with_spectrum(const std::function<model::ModelPtr(int)>& make,
                                              const data::DynamicTestTable& raw, MasterCurve curve,
                                              const FitOptions& options, const SpectrumOptions& spectrum,
                                              int max_rounds) {
  const core::Stopwatch clock;
  SpectrumMasterFit out;
  out.spectrum = fit_spectrum(make, curve.master, options, spectrum);
  out.pairwise_cost = storage_cost(out.spectrum.result, curve.master, options);
  double cost = out.pairwise_cost;
  std::vector<double> temperatures;
  for (const auto& iso : curve.isotherms) temperatures.push_back(iso.temperature_C);
  const int anchor = detail::nearest_temperature(temperatures, curve.reference_C);
  for (int round = 0; round < max_rounds; ++round) {
    // Each shift but the anchor's on its own rows, the spectrum held (within ±0.5 decade).
    std::vector<double> shifts;
    for (int k = 0; k < static_cast<int>(curve.isotherms.size()); ++k) {
      const IsothermShift& iso = curve.isotherms[k];
      if (k == anchor) {
        shifts.push_back(iso.log10_aT);
        continue;
      }
      auto cost = [&](double d) {
        return isotherm_cost(out.spectrum.result, raw, iso, curve.reference_C, d, storage_only(options));
      };
      const auto [d, c] = boost::math::tools::brent_find_minima(cost, iso.log10_aT - 0.5, iso.log10_aT + 0.5, kBrentBits);
      shifts.push_back(c < cost(iso.log10_aT) ? d : iso.log10_aT);
    }
    MasterCurve moved = curve;
    apply_shifts(moved, raw, shifts);
    SpectrumFit next = fit_spectrum(make, moved.master, options, spectrum);
    const double next_cost = storage_cost(next.result, moved.master, options);
    if (!(next_cost < cost * (1.0 - 1e-4))) break;
    cost = next_cost;
    curve = std::move(moved);
    out.spectrum = std::move(next);
    ++out.rounds;
  }
  std::ostringstream s;
  s << "isotherm shifts refined with the smooth spectrum: " << out.rounds << " round(s), storage cost "
    << out.pairwise_cost << " -> " << cost << " (anchor " << curve.isotherms[anchor].temperature_C << " degC held)";
  curve.messages.push_back(s.str());
  out.spectrum.result.messages.push_back(s.str());
  out.curve = std::move(curve);
  out.spectrum.wall_time_s = clock.seconds();
  return out;
}

}  // namespace fitlib::fit
