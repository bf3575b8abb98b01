// Admissible window and quality verdict of relaxation fits (docs/fitting.md "Relaxation data").
#include "relaxation_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "admissible.hpp"
#include "quality.hpp"

namespace fitlib::fit::detail {

model::DataSummary summarize_relaxation(const data::RelaxationTable& table) {
  model::DataSummary s;
  double t_min = HUGE_VAL, t_max = 0.0, m_min = HUGE_VAL, m_max = 0.0;
  s.temperature_min_C = HUGE_VAL;
  s.temperature_max_C = -HUGE_VAL;
  for (const auto& r : table.rows) {
    t_min = std::min(t_min, r.time_s);
    t_max = std::max(t_max, r.time_s);
    m_min = std::min(m_min, r.modulus_MPa);
    m_max = std::max(m_max, r.modulus_MPa);
    if (!std::isnan(r.temperature_C)) {
      s.temperature_min_C = std::min(s.temperature_min_C, r.temperature_C);
      s.temperature_max_C = std::max(s.temperature_max_C, r.temperature_C);
    }
  }
  if (s.temperature_min_C > s.temperature_max_C) s.temperature_min_C = s.temperature_max_C = 23.0;
  // A relaxation time τ is seen at t ≈ τ, as a frequency ω ≈ 1/τ is.
  s.omega_min_rad_s = 1.0 / t_max;
  s.omega_max_rad_s = 1.0 / t_min;
  s.storage_min_MPa = m_min;
  s.storage_max_MPa = m_max;
  return s;
}

AdmissibleWindow relaxation_window(const model::Model& model, const data::RelaxationTable& table,
                                   const FitOptions& options) {
  const SeriesTerms series = series_terms(model.parameters());
  if (series.empty() || table.rows.empty() || model.temperature_law_info().law != model::ShiftLaw::none) return {};
  const model::DataSummary s = summarize_relaxation(table);
  AdmissibleWindow w = window_over(series, model.parameters(), options, s.omega_min_rad_s, s.omega_max_rad_s,
                                   s.storage_min_MPa, s.storage_max_MPa);
  // A term is seen in M(t) as exp(−t/τ): at τ = t_min/ln 100 it still shows 1 % of its modulus at
  // the first time, as a Maxwell term at τ = 1/(10 ω_max) shows 1 % of its in E′(ω_max). The
  // frequency rule's t_min/10 hid a term at exp(−10) = 4.5e-5, free to take the ceiling's modulus
  // (docs/decisions.md "Relaxation window: the same visibility at its short edge").
  const double t_min_s = 1.0 / s.omega_max_rad_s;
  w.tau_min_s = std::max(w.tau_min_s, t_min_s / (std::log(100.0) * std::pow(10.0, options.tau_margin_decades - 1.0)));
  return w;
}

std::pair<double, double> window_bounds(const model::Model& model, const AdmissibleWindow& w, int i) {
  const auto& spec = model.parameters()[i];
  if (!w.applies) return {spec.lower, spec.upper};
  const auto limits = window_limits(series_terms(model.parameters()), w, i);
  if (!limits) return {spec.lower, spec.upper};
  return {std::max(spec.lower, limits->first), std::min(spec.upper, limits->second)};
}

QualityVerdict relaxation_verdict(const model::Model& model, const std::vector<double>& p,
                                  const data::RelaxationTable& table) {
  const QualityThresholds th;
  ErrorFigures fig;
  fig.group = "all";
  fig.modulus = "relaxation";
  double worst_t = 0.0;
  for (const auto& row : table.rows) {
    model::TestCondition c;
    c.mode = row.mode;
    c.temperature_C = row.temperature_C;
    const double err = std::abs(model.relaxation_modulus(p.data(), c, row.time_s) / row.modulus_MPa - 1.0);
    ++fig.count;
    fig.mean_rel_error += err;
    if (err >= fig.max_rel_error) fig.max_rel_error = err, worst_t = row.time_s;
  }
  fig.mean_rel_error /= std::max(fig.count, 1);
  fig.max_at_frequency_Hz = worst_t > 0.0 ? 1.0 / (2.0 * M_PI * worst_t) : 0.0;
  QualityVerdict v;
  v.figures.push_back(fig);
  if (fig.mean_rel_error > th.storage_mean || fig.max_rel_error > th.storage_max) {
    std::ostringstream s;
    s.precision(3);
    s << "fit misses the relaxation modulus M(t): mean relative error " << 100.0 * fig.mean_rel_error << " %, max "
      << 100.0 * fig.max_rel_error << " % at t = " << worst_t << " s (thresholds " << 100.0 * th.storage_mean
      << " %, " << 100.0 * th.storage_max << " %)";
    v.warnings.push_back(s.str());
  }
  return v;
}

}  // namespace fitlib::fit::detail
