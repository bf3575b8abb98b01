// Life as a distribution per mode: B10 and B50 with the constants' uncertainty (life_distribution.hpp).
#include "fitlib/fatigue/life_distribution.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace fitlib::fatigue {

namespace {

constexpr double kLn10 = 2.30258509299404568, kLog10Of2 = 0.30102999566398120;

// z_p of the standard normal: the life by which p % have failed lies z_p s below the median.
double normal_quantile(double percent) {
  return boost::math::quantile(boost::math::normal(), percent / 100.0);
}

// B_p = N_law 10^(z_p s): B50 is the deterministic life to the bit.
BLife b_life(double percent, double median_cycles, const ModeDistribution& d, bool with_interval,
             double cycles_per_hour) {
  BLife b;
  b.percent = percent;
  const double shift = normal_quantile(percent) * d.sigma_log10;
  b.cycles = median_cycles * std::pow(10.0, shift);
  b.has_hours = cycles_per_hour > 0.0;
  const double per_h = b.has_hours ? cycles_per_hour : HUGE_VAL;  // 0 h where hours are not known
  b.h = b.cycles / per_h;
  b.has_interval = with_interval;
  if (!with_interval) return b;
  // Student t with the scatter's degrees of freedom: the covariance is s²(JᵀJ)⁻¹ with s estimated.
  const double t = d.dof > 0 ? boost::math::quantile(boost::math::students_t(d.dof), 0.95) : normal_quantile(95.0);
  b.low_cycles = median_cycles * std::pow(10.0, shift - t * d.constants_sd_log10);
  b.high_cycles = median_cycles * std::pow(10.0, shift + t * d.constants_sd_log10);
  b.low_h = b.low_cycles / per_h, b.high_h = b.high_cycles / per_h;
  return b;
}

}  // namespace

std::array<double, 3> log10_life_gradient(const std::vector<double>& peaks_MPa, const LifeLaw& law, double dT) {
  // ln S = ln Σ (σ_i/σ0)ⁿ; ∂ln S/∂ln σ0 = −n, ∂ln S/∂n = Σ w_i ln(σ_i/σ0) with w_i the terms' shares.
  double top = -HUGE_VAL;
  for (double p : peaks_MPa) top = std::max(top, law.n * std::log(p / law.sigma0_MPa));
  double sum = 0.0, weighted = 0.0;
  for (double p : peaks_MPa) {
    const double x = std::log(p / law.sigma0_MPa), w = std::exp(law.n * x - top);
    sum += w, weighted += w * x;
  }
  return {law.n / kLn10, -(weighted / sum) / kLn10, -dT * kLog10Of2};
}

std::optional<ModeDistribution> mode_distribution(const ModeLife& m, const LifeLaw& law, double temperature_C,
                                                  double reference_C, double cycles_per_hour) {
  if (!law.scatter || !std::isfinite(m.life_cycles) || m.peaks.empty()) return std::nullopt;
  ModeDistribution d;
  d.mode = m.mode;
  d.sigma_log10 = law.scatter->sigma_log10;
  d.dof = law.scatter->dof;
  if (law.covariance) {
    std::vector<double> peaks;
    for (const Peak& p : m.peaks) peaks.push_back(p.stress_MPa);
    const auto g = log10_life_gradient(peaks, law, temperature_C - reference_C);
    double var = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) var += g[i] * (*law.covariance)[i][k] * g[k];
    d.constants_sd_log10 = std::sqrt(std::max(var, 0.0));
  }
  // the deterministic life is the median
  d.b10 = b_life(10.0, m.life_cycles, d, law.covariance.has_value(), cycles_per_hour);
  d.b50 = b_life(50.0, m.life_cycles, d, law.covariance.has_value(), cycles_per_hour);
  return d;
}

namespace {

// The q-quantile of sorted values, linear between order statistics (Hyndman–Fan type 7).
double sorted_quantile(const std::vector<double>& x, double q) {
  const double at = q * static_cast<double>(x.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, x.size() - 1);
  if (!std::isfinite(x[hi])) return x[hi] > 0.0 && at > static_cast<double>(lo) ? x[hi] : x[lo];
  return x[lo] + (at - static_cast<double>(lo)) * (x[hi] - x[lo]);
}

// Cycles per hour of a B life (∞ where hours are not known: 0 h).
double per_hour(const BLife& b) { return b.has_hours ? b.cycles / b.h : HUGE_VAL; }

void set_cards_interval(BLife& b, const std::vector<double>& sorted_cycles, double shift) {
  b.has_cards_interval = !sorted_cycles.empty();
  if (!b.has_cards_interval) return;
  const double factor = std::pow(10.0, shift);
  b.cards_low_cycles = sorted_quantile(sorted_cycles, 0.05) * factor;
  b.cards_high_cycles = sorted_quantile(sorted_cycles, 0.95) * factor;
  const double per_h = per_hour(b);
  b.cards_low_h = b.cards_low_cycles / per_h, b.cards_high_h = b.cards_high_cycles / per_h;
}

// The constants' error in units of its standard deviation: Student t with the scatter's degrees of
// freedom, as the constants' own interval (b_life), the normal without; the lower tail by symmetry.
double constants_cdf(double u, int dof) {
  return dof > 0 ? boost::math::cdf(boost::math::students_t(dof), u) : boost::math::cdf(boost::math::normal(), u);
}
double constants_quantile(double p, int dof) {
  if (p < 0.5) return -constants_quantile(1.0 - p, dof);
  return dof > 0 ? boost::math::quantile(boost::math::students_t(dof), p) : normal_quantile(100.0 * p);
}

// The q-quantile of F(x) = (1/J) Σ_j F_T((x − y_j)/sd) over the draws' sorted log10 lives y (+∞
// for an unbounded draw, which adds no mass below any x). Bisection inside the bracket where every
// finite term is at most q (x = y_min + sd Q(q)) and at least q J/J_finite; +∞ when the finite
// draws' mass cannot reach q.
double combined_quantile(const std::vector<double>& y, double sd, int dof, double q) {
  std::size_t finite = 0;
  while (finite < y.size() && std::isfinite(y[finite])) ++finite;
  const double reach = finite ? q * static_cast<double>(y.size()) / static_cast<double>(finite) : HUGE_VAL;
  if (reach >= 1.0) return HUGE_VAL;
  auto cdf = [&](double x) {
    double sum = 0.0;
    for (std::size_t j = 0; j < finite; ++j) sum += constants_cdf((x - y[j]) / sd, dof);
    return sum / static_cast<double>(y.size());
  };
  double lo = y.front() + sd * constants_quantile(q, dof), hi = y[finite - 1] + sd * constants_quantile(reach, dof);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    (cdf(mid) < q ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

void add_cards_interval(ModeDistribution& d, std::vector<double> draw_cycles, const CardsSampling& sampling) {
  std::sort(draw_cycles.begin(), draw_cycles.end());
  d.cards = sampling;
  d.cards->median_cycles = draw_cycles.empty() ? NAN : sorted_quantile(draw_cycles, 0.5);
  set_cards_interval(d.b10, draw_cycles, normal_quantile(10.0) * d.sigma_log10);
  set_cards_interval(d.b50, draw_cycles, 0.0);
}

void add_combined_interval(ModeDistribution& d, const std::vector<double>& draw_cycles) {
  if (draw_cycles.empty()) return;
  std::vector<double> y;
  for (double n : draw_cycles) y.push_back(std::log10(n));
  std::sort(y.begin(), y.end());
  const double sd = d.constants_sd_log10;
  for (auto [b, shift] : {std::pair{&d.b10, normal_quantile(10.0) * d.sigma_log10}, std::pair{&d.b50, 0.0}}) {
    b->has_combined_interval = true;
    if (!(sd > 0.0)) {  // no constants' covariance: the cards' interval alone
      b->combined_low_cycles = b->cards_low_cycles, b->combined_high_cycles = b->cards_high_cycles;
    } else {
      b->combined_low_cycles = std::pow(10.0, combined_quantile(y, sd, d.dof, 0.05) + shift);
      b->combined_high_cycles = std::pow(10.0, combined_quantile(y, sd, d.dof, 0.95) + shift);
    }
    const double per_h = per_hour(*b);
    b->combined_low_h = b->combined_low_cycles / per_h, b->combined_high_h = b->combined_high_cycles / per_h;
  }
}

std::vector<ModeDistribution> life_distribution(const LifeReport& report, const FatigueCard& card,
                                                const LifeConditions& conditions) {
  std::vector<ModeDistribution> out;
  for (const ModeLife& m : report.modes)
    if (auto d = mode_distribution(m, card.law(m.mode), conditions.temperature_C, card.reference_temperature_C,
                                   conditions.cycles_per_hour))
      out.push_back(*d);
  return out;
}

namespace {

std::string b_text(const BLife& b) {
  const bool hours = b.has_hours;
  char buf[160];
  const double x = hours ? b.h : b.cycles, lo = hours ? b.low_h : b.low_cycles, hi = hours ? b.high_h : b.high_cycles;
  const char* unit = hours ? "h" : "cycles";
  if (b.has_interval)
    std::snprintf(buf, sizeof buf, "B%.0f %.4g %s [%.4g, %.4g]", b.percent, x, unit, lo, hi);
  else
    std::snprintf(buf, sizeof buf, "B%.0f %.4g %s", b.percent, x, unit);
  std::string out = buf;
  if (b.has_cards_interval) {
    std::snprintf(buf, sizeof buf, " cards [%.4g, %.4g]", hours ? b.cards_low_h : b.cards_low_cycles,
                  hours ? b.cards_high_h : b.cards_high_cycles);
    out += buf;
  }
  if (b.has_combined_interval) {
    std::snprintf(buf, sizeof buf, " combined [%.4g, %.4g]", hours ? b.combined_low_h : b.combined_low_cycles,
                  hours ? b.combined_high_h : b.combined_high_cycles);
    out += buf;
  }
  return out;
}

// What the cards' interval rests on: draws, seed, failures and the draws' median life.
std::string cards_text(const ModeDistribution& d) {
  const CardsSampling& c = *d.cards;
  char buf[200];
  if (c.failed == c.samples)
    std::snprintf(buf, sizeof buf, "%-13s cards: none of %d draws (seed %llu) ran, so no cards' interval", "", c.samples,
                  static_cast<unsigned long long>(c.seed));
  else
    std::snprintf(buf, sizeof buf, "%-13s cards: %d draws (seed %llu), their median life %.4g cycles against the "
                  "law's %.4g", "", c.samples, static_cast<unsigned long long>(c.seed), c.median_cycles, d.b50.cycles);
  std::string out = buf;
  if (c.failed > 0) out += "; " + std::to_string(c.failed) + " draws did not run (first: " + c.first_failure + ")";
  return out + "\n";
}

}  // namespace

std::string life_distribution_table(const LifeReport& report, const std::vector<ModeDistribution>& dist) {
  std::string out, without;
  for (const ModeLife& m : report.modes) {
    if (!std::isfinite(m.life_cycles)) continue;
    const ModeDistribution* d = nullptr;
    for (const ModeDistribution& x : dist)
      if (x.mode == m.mode) d = &x;
    if (!d) {
      without += (without.empty() ? "" : " and ") + std::string(to_string(m.mode));
      continue;
    }
    char head[160];
    std::snprintf(head, sizeof head, "%-13s log-normal, s %.3g log10 (%d dof): ", to_string(m.mode), d->sigma_log10,
                  d->dof);
    out += std::string(head) + b_text(d->b10) + ", " + b_text(d->b50) +
           (d->b10.has_interval ? " (90 % intervals: the constants' covariance" : " (no interval of the constants: the "
                                                                                  "card has no covariance of them") +
           (d->cards ? std::string("; cards: the material cards' covariance") : std::string()) +
           (d->b50.has_combined_interval ? std::string("; combined: both as one distribution") : std::string()) +
           ")\n";
    if (d->cards) out += cards_text(*d);
  }
  if (!without.empty())
    out += "distribution: the fatigue card states no scatter of the " + without + " lives (fitcli life-fit "
           "writes it), so the lives above are medians without B10\n";
  return out;
}

nlohmann::json life_distribution_json(const std::vector<ModeDistribution>& dist) {
  using nlohmann::json;
  json out = json::array();
  // An interval's end beyond every drawn life (unbounded draws) is null, as an unbounded life is.
  auto range = [](double lo, double hi) {
    return json::array({std::isfinite(lo) ? json(lo) : json(nullptr), std::isfinite(hi) ? json(hi) : json(nullptr)});
  };
  for (const ModeDistribution& d : dist) {
    json modes = {{"mode", to_string(d.mode)}, {"distribution", "lognormal"}, {"sigma_log10", d.sigma_log10},
                  {"dof", d.dof}, {"constants_sd_log10", d.constants_sd_log10}};
    for (const BLife* b : {&d.b10, &d.b50}) {
      json e = {{"cycles", b->cycles}};
      if (b->has_hours) e["h"] = b->h;
      if (b->has_interval) e["ci90_cycles"] = {b->low_cycles, b->high_cycles};
      if (b->has_interval && b->has_hours) e["ci90_h"] = {b->low_h, b->high_h};
      if (b->has_cards_interval) e["ci90_cards_cycles"] = range(b->cards_low_cycles, b->cards_high_cycles);
      if (b->has_cards_interval && b->has_hours) e["ci90_cards_h"] = range(b->cards_low_h, b->cards_high_h);
      if (b->has_combined_interval) e["ci90_combined_cycles"] = range(b->combined_low_cycles, b->combined_high_cycles);
      if (b->has_combined_interval && b->has_hours) e["ci90_combined_h"] = range(b->combined_low_h, b->combined_high_h);
      modes[b->percent < 50.0 ? "B10" : "B50"] = e;
    }
    if (d.cards)
      modes["cards_sampling"] = {{"draws", d.cards->samples}, {"failed", d.cards->failed}, {"seed", d.cards->seed},
                                 {"median_cycles", std::isfinite(d.cards->median_cycles) ? json(d.cards->median_cycles) : json(nullptr)}};
    out.push_back(modes);
  }
  return out;
}

}  // namespace fitlib::fatigue
