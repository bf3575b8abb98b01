#include "fitlib/fatigue/life.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fatigue/crack_plane.hpp"

namespace fitlib::fatigue {

double sum_terms(const std::vector<double>& peaks, const LifeLaw& law) {
  double s = 0.0;
  for (double p : peaks) s += std::pow(p / law.sigma0_MPa, law.n);
  return s;
}

double temperature_factor(const LifeLaw& law, double temperature_C, double reference_C) {
  return std::exp2(-law.b_per_C * (temperature_C - reference_C));
}

std::vector<double> effective_stress_history(const PointHistory& p, double sweep_deg) {
  const double sweep = sweep_deg * core::kPi / 180.0;
  std::vector<double> out;
  out.reserve(p.samples.size());
  for (const StressSample& s : p.samples) {
    const PlaneStress ps{s.s11_MPa, s.s22_MPa, s.s12_MPa};
    if (!std::isfinite(ps.s11_MPa) || !std::isfinite(ps.s22_MPa) || !std::isfinite(ps.s12_MPa))
      throw core::NumericalError("fatigue: non-finite stress at point '" + p.name + "', t = " +
                                 core::format_number(s.t_s) + " s");
    out.push_back(p.role == Role::bottom ? worst_radial_crack_stress_MPa(ps, sweep)
                                         : separation_stress_MPa(ps));
  }
  return out;
}

namespace {

Mode mode_of(Role r) { return r == Role::bottom ? Mode::radial_crack : Mode::separation; }

// The samples of the last load cycle.
PointHistory last_cycle(const PointHistory& p, double cycle_time_s) {
  for (std::size_t i = 1; i < p.samples.size(); ++i)
    if (p.samples[i].t_s < p.samples[i - 1].t_s)
      throw core::InputError("stress history times decrease at sample " + std::to_string(i), "",
                             0, 0, "points." + p.name);
  PointHistory out = p;
  if (cycle_time_s > 0.0 && !p.samples.empty()) {
    const double t0 = p.samples.back().t_s - cycle_time_s;
    out.samples.clear();
    for (const StressSample& s : p.samples)
      if (s.t_s > t0) out.samples.push_back(s);
  }
  if (out.samples.empty())
    throw core::InputError("no stress samples in the last load cycle", "", 0, 0, "points." + p.name);
  return out;
}

std::string share_at(const std::vector<CycleShare>& shares, double t_in_cycle) {
  for (const CycleShare& c : shares)
    if (t_in_cycle >= c.t_begin_s && t_in_cycle < c.t_end_s) return c.name;
  for (const CycleShare& c : shares)  // the cycle's last instant closes the last share
    if (t_in_cycle == c.t_end_s) return c.name;
  return "";
}

// Miner: the damage per cycle of one peak added to its pulley's share.
void add_damage(std::vector<ShareDamage>& shares, const std::string& pulley, double damage) {
  auto it = std::find_if(shares.begin(), shares.end(),
                         [&](const ShareDamage& s) { return s.name == pulley; });
  if (it == shares.end()) shares.push_back({pulley, damage});
  else it->damage_per_cycle += damage;
}

// Samples in the contiguous run around `index` at or above `level` (the history is one cycle).
int samples_at_or_above(const std::vector<double>& v, std::size_t index, double level) {
  int n = 1;
  for (std::size_t i = index; i > 0 && v[i - 1] >= level; --i) ++n;
  for (std::size_t i = index + 1; i < v.size() && v[i] >= level; ++i) ++n;
  return n;
}

ModeLife point_life(const PointHistory& p, const FatigueCard& card, const LifeConditions& c) {
  const PointHistory cycle = last_cycle(p, c.cycle_time_s);
  const Mode mode = mode_of(p.role);
  const LifeLaw& law = card.law(mode);
  ModeLife m;
  m.mode = mode;
  m.design_point = p.name;
  m.x_mm = p.x_mm;
  m.y_mm = p.y_mm;
  m.element = p.element, m.integration_point = p.integration_point;
  m.effective_stress_MPa = effective_stress_history(cycle, card.crack_sweep_deg);
  const double t_start = c.cycle_time_s > 0.0 ? p.samples.back().t_s - c.cycle_time_s
                                              : cycle.samples.front().t_s;
  for (const StressSample& s : cycle.samples) m.t_s.push_back(s.t_s);
  std::size_t dominant = 0;
  for (const Extremum& e : significant_peaks(m.effective_stress_MPa, c.peaks)) {
    const double t = m.t_s[e.index];
    if (m.peaks.empty() || e.value > m.peaks[dominant].stress_MPa)
      dominant = m.peaks.size(), m.dominant_peak_samples = samples_at_or_above(m.effective_stress_MPa, e.index,
                                                                               e.value * std::exp2(-1.0 / law.n));
    m.peaks.push_back({t, e.value, share_at(c.pulleys, t - t_start)});
  }
  m.temperature_factor = temperature_factor(law, c.temperature_C, card.reference_temperature_C);
  for (const Peak& pk : m.peaks) {
    const double term = std::pow(pk.stress_MPa / law.sigma0_MPa, law.n);
    m.sum_terms += term;
    add_damage(m.shares, pk.pulley, term / m.temperature_factor);
  }
  if (m.sum_terms > 0.0) {
    m.largest_peak_over_sigma0 = m.peaks[dominant].stress_MPa / law.sigma0_MPa;
    m.dominant_peak_share = std::pow(m.largest_peak_over_sigma0, law.n) / m.sum_terms;
    m.life_cycles = m.temperature_factor / m.sum_terms;
    if (c.cycles_per_hour > 0.0) m.life_h = m.life_cycles / c.cycles_per_hour;
  }
  return m;
}

}  // namespace

bool peak_under_resolved(const ModeLife& m) {
  return m.dominant_peak_share > 0.9 && m.dominant_peak_samples < 3;
}

std::vector<std::string> life_warnings(const LifeReport& r, bool points_have_history) {
  std::vector<std::string> out;
  for (const ModeLife& m : r.modes)
    if (points_have_history && peak_under_resolved(m))
      out.push_back(std::string("the ") + to_string(m.mode) + " life is " +
                    core::format_number(100.0 * m.dominant_peak_share, 3) + " % one peak carried by " +
                    std::to_string(m.dominant_peak_samples) +
                    " sample(s): the increments may miss its top, and the life moves with the peak to the life "
                    "exponent's power (docs/segment.md \"The driver exit's peel transient\")");
  // A life outside the range (6.31) was fitted over: "the MODE life, N load cycles, is WHERE LIMIT: …".
  auto unreadable = [](const ModeLife& m, const char* where, double limit, const char* fitted_and_reading) {
    return std::string("the ") + to_string(m.mode) + " life, " + core::format_number(m.life_cycles, 4) +
           " load cycles, is " + where + " " + core::format_number(limit) + ": its largest peak is " +
           core::format_number(m.largest_peak_over_sigma0, 3) + " x sigma0, and the life law (6.31) was fitted to " +
           fitted_and_reading;
  };
  for (const ModeLife& m : r.modes)
    if (m.life_cycles < kShortestReadableLife_cycles)
      out.push_back(unreadable(m, "below", kShortestReadableLife_cycles,
                               "belts that ran for hours; read it as failure at once, not as a number (are the cards "
                               "a belt rubber's at this temperature?)"));
  for (const ModeLife& m : r.modes)
    if (std::isfinite(m.life_cycles) && m.life_cycles > kLongestReadableLife_cycles)
      out.push_back(unreadable(m, "beyond", kLongestReadableLife_cycles,
                               "belts that lived 1-2000 h (Report III; real drives live 10-100 times longer); read it "
                               "as no fatigue failure in this mode at this load (a runout), not as a number"));
  return out;
}

std::vector<double> cycle_peaks_MPa(const PointHistory& p, double crack_sweep_deg,
                                    const LifeConditions& c) {
  const std::vector<double> se =
      effective_stress_history(last_cycle(p, c.cycle_time_s), crack_sweep_deg);
  std::vector<double> out;
  for (const Extremum& e : significant_peaks(se, c.peaks)) out.push_back(e.value);
  return out;
}

CordBreakLife cord_break_life(const std::vector<double>& force_N, const CordBreakLaw& law,
                              double temperature_C, double reference_C, double cycles_per_hour) {
  if (force_N.empty())
    throw core::InputError("the cord-break law needs the belt force over the cycle", "", 0, 0,
                           "cord_break");
  const auto [lo, hi] = std::minmax_element(force_N.begin(), force_N.end());
  CordBreakLife r;
  r.mean_MPa = 0.5 * (*hi + *lo) / law.cord_area_mm2;
  r.amplitude_MPa = 0.5 * (*hi - *lo) / law.cord_area_mm2;
  if (r.mean_MPa >= law.ultimate_MPa)
    throw core::InputError("mean cord stress " + std::to_string(r.mean_MPa) +
                               " MPa reaches the ultimate stress", "", 0, 0, "cord_break.ultimate_MPa");
  r.equivalent_amplitude_MPa = r.amplitude_MPa / (1.0 - r.mean_MPa / law.ultimate_MPa);  // (3.6)
  r.life_cycles = std::pow(10.0, law.a - law.b_per_MPa * r.equivalent_amplitude_MPa) *
                  std::exp2(-law.b_T_per_C * (temperature_C - reference_C));  // (3.7)
  if (cycles_per_hour > 0.0) r.life_h = r.life_cycles / cycles_per_hour;
  return r;
}

LifeReport evaluate_life(const std::vector<PointHistory>& points, const FatigueCard& card,
                         const LifeConditions& c) {
  LifeReport report;
  for (Mode mode : {Mode::radial_crack, Mode::separation}) {
    std::optional<ModeLife> best;  // the first of equal sums: a named point before a scanned one
    int candidates = 0;
    for (const PointHistory& p : points) {
      if (mode_of(p.role) != mode) continue;
      ModeLife m = point_life(p, card, c);
      ++candidates;
      if (!best || m.sum_terms > best->sum_terms) best = std::move(m);
    }
    if (best) best->points_evaluated = candidates, report.modes.push_back(std::move(*best));
  }
  for (const ModeLife& m : report.modes)
    if (m.life_cycles < report.life_cycles) {
      report.life_cycles = m.life_cycles;
      report.life_h = m.life_h;
      report.governing = to_string(m.mode);
    }
  if (card.cord_break) {
    report.cord_break = cord_break_life(c.cord_force_N, *card.cord_break, c.temperature_C,
                                        card.reference_temperature_C, c.cycles_per_hour);
    if (report.cord_break->life_cycles < report.life_cycles) {
      report.life_cycles = report.cord_break->life_cycles;
      report.life_h = report.cord_break->life_h;
      report.governing = "cord_break";
    }
  }
  return report;
}

namespace {

nlohmann::json finite_or_null(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

}  // namespace

namespace {

std::string life_text(double cycles, double hours, int digits = 4) {
  if (!std::isfinite(cycles)) return "unbounded";
  char buf[96];
  if (std::isfinite(hours)) std::snprintf(buf, sizeof buf, "%.*g cycles (%.*g h)", digits, cycles, digits, hours);
  else std::snprintf(buf, sizeof buf, "%.*g cycles", digits, cycles);
  return buf;
}

}  // namespace

std::string life_table(const LifeReport& r) {
  std::string out;
  char buf[256];
  for (const ModeLife& m : r.modes) {
    char of[64] = "";
    if (m.points_evaluated > 1) std::snprintf(of, sizeof of, ", worst of %d points", m.points_evaluated);
    std::snprintf(buf, sizeof buf, "%-13s %-32s design point %s (x %.3g, y %.3g mm%s), %zu peaks, "
                  "sum (s/s0)^n %.4g\n", to_string(m.mode),
                  life_text(m.life_cycles, m.life_h, m.significant_digits).c_str(), m.design_point.c_str(), m.x_mm,
                  m.y_mm, of, m.peaks.size(), m.sum_terms);
    out += buf;
    if (!m.beyond_tests.empty()) out += "              beyond the tests: " + m.beyond_tests + "\n";
  }
  int governing_digits = 4;
  for (const ModeLife& m : r.modes)
    if (r.governing == to_string(m.mode)) governing_digits = m.significant_digits;
  if (r.cord_break) {
    const CordBreakLife& k = *r.cord_break;
    std::snprintf(buf, sizeof buf, "%-13s %-32s mean %.4g MPa, amplitude %.4g MPa\n", "cord_break",
                  life_text(k.life_cycles, k.life_h).c_str(), k.mean_MPa, k.amplitude_MPa);
    out += buf;
  }
  out += "governing: " + r.governing + ", " + life_text(r.life_cycles, r.life_h, governing_digits) + "\n";
  return out;
}

nlohmann::json life_to_json(const LifeReport& r, bool effective_stress_history) {
  using nlohmann::json;
  json modes = json::array();
  for (const ModeLife& m : r.modes) {
    json peaks = json::array(), shares = json::array();
    for (const Peak& p : m.peaks)
      peaks.push_back({{"t_s", p.t_s}, {"effective_stress_MPa", p.stress_MPa}, {"pulley", p.pulley}});
    for (const ShareDamage& s : m.shares)
      shares.push_back({{"pulley", s.name}, {"damage_per_cycle", s.damage_per_cycle}});
    json point = {{"name", m.design_point}, {"x_mm", m.x_mm}, {"y_mm", m.y_mm}, {"points_evaluated", m.points_evaluated}};
    if (m.element >= 0) point["element"] = m.element;
    if (m.integration_point >= 0) point["integration_point"] = m.integration_point;
    modes.push_back({{"mode", to_string(m.mode)},
                     {"design_point", point},
                     {"sum_terms", m.sum_terms},
                     {"temperature_factor", m.temperature_factor},
                     {"life_cycles", finite_or_null(m.life_cycles)},
                     {"life_h", finite_or_null(m.life_h)},
                     {"unbounded", !std::isfinite(m.life_cycles)},
                     {"peaks", peaks},
                     {"miner_shares", shares}});
    if (!m.beyond_tests.empty()) modes.back()["beyond_tests"] = m.beyond_tests, modes.back()["extrapolated"] = true;
    if (effective_stress_history)
      modes.back()["effective_stress"] = {{"t_s", m.t_s}, {"MPa", m.effective_stress_MPa}};
  }
  json j = {{"modes", modes},
            {"governing_mode", r.governing},
            {"life_cycles", finite_or_null(r.life_cycles)},
            {"life_h", finite_or_null(r.life_h)},
            {"unbounded", !std::isfinite(r.life_cycles)}};
  if (r.cord_break) {
    const CordBreakLife& k = *r.cord_break;
    j["cord_break"] = {{"mean_MPa", k.mean_MPa}, {"amplitude_MPa", k.amplitude_MPa},
                       {"equivalent_amplitude_MPa", k.equivalent_amplitude_MPa},
                       {"life_cycles", finite_or_null(k.life_cycles)},
                       {"life_h", finite_or_null(k.life_h)}};
  }
  return j;
}

}  // namespace fitlib::fatigue
