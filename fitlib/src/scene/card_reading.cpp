// How the life's segment levels read the cards (docs/fatigue.md §8 "The cards at the amplitude the
// segment drives them"): the strain amplitude each role reached, the cards read at it, and what a
// reading beyond the cards' tests does to the result (docs/decisions.md "Life: one policy for a card
// driven beyond its tests").
#include "card_reading.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/card/data_window.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::scene {

std::optional<double> CardReading::beyond_tests_factor() const {
  if (!largest_tested_amplitude || !(*largest_tested_amplitude > 0.0) || !(reached_amplitude > *largest_tested_amplitude))
    return std::nullopt;
  return reached_amplitude / *largest_tested_amplitude;
}

namespace detail {
namespace {

// The deviatoric part's norm of an in-plane strain difference (e11, e22, 2 e12; e33 = 0): the
// measure a pair of instants is chosen by.
double deviatoric_norm(const std::array<double, 3>& d) {
  const double mean = (d[0] + d[1]) / 3.0;
  const double a = d[0] - mean, b = d[1] - mean, c = -mean, e12 = 0.5 * d[2];
  return std::sqrt(a * a + b * b + c * c + 2.0 * e12 * e12);
}

// One point's last cycle: the half range of each component, and the half difference (with signs)
// between the two instants whose deviatoric strains lie furthest apart.
void point_amplitude(const segment::MonitoredHistory& m, double cycle_time_s, ReachedAmplitude& out) {
  std::vector<std::array<double, 3>> e;
  const double from_s = m.samples.back().t_s - cycle_time_s;
  for (const segment::CycleSample& c : m.samples)
    if (c.t_s >= from_s) e.push_back({c.e11, c.e22, 2.0 * c.e12});
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& x : e)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  double half_range = 0.0;
  for (int k = 0; k < 3; ++k) half_range = std::max(half_range, 0.5 * (hi[k] - lo[k]));
  if (half_range > out.strain_amplitude) out.strain_amplitude = half_range;
  for (std::size_t i = 0; i < e.size(); ++i)
    for (std::size_t j = i + 1; j < e.size(); ++j) {
      const std::array<double, 3> d = {0.5 * (e[i][0] - e[j][0]), 0.5 * (e[i][1] - e[j][1]), 0.5 * (e[i][2] - e[j][2])};
      const double n = deviatoric_norm(d);
      if (n > out.deviatoric_norm) out.deviatoric_norm = n, out.components = d;
    }
}

}  // namespace

std::map<std::string, ReachedAmplitude> reached_amplitudes(const segment::CycleResult& run) {
  std::map<std::string, ReachedAmplitude> by_role;
  for (const segment::MonitoredHistory& m : run.points)
    if (!m.samples.empty())
      point_amplitude(m, run.cycle_time_s, by_role[core::to_string(m.role)]);
  return by_role;
}

std::vector<ReachedAmplitude> element_amplitudes(const segment::CycleResult& run) {
  std::vector<ReachedAmplitude> out(run.element_means.size());
  for (std::size_t e = 0; e < run.element_means.size(); ++e)
    if (!run.element_means[e].samples.empty()) point_amplitude(run.element_means[e], run.cycle_time_s, out[e]);
  return out;
}

model::Vector6 voigt_amplitude(const ReachedAmplitude& a) {
  model::Vector6 v = model::Vector6::Zero();
  v[0] = a.components[0], v[1] = a.components[1], v[5] = a.components[2];
  return v;
}

std::vector<CardReading> card_readings(const Scene& s, core::Fidelity fidelity, double frequency_Hz,
                                       const std::map<std::string, ReachedAmplitude>& reached,
                                       const std::map<std::string, ReachedAmplitude>& read_at) {
  std::vector<CardReading> out;
  for (const char* role : kSegmentRoles) {
    if (!s.materials.count(role) || !reached.count(role)) continue;
    CardReading c;
    c.role = role, c.card = s.materials.at(role), c.temperature_C = s.temperature_C;
    if (fidelity == core::Fidelity::elastic) c.frequency_Hz = frequency_Hz;
    if (auto it = read_at.find(role); it != read_at.end())
      c.read_at = it->second.components, c.read_amplitude = it->second.strain_amplitude;
    c.reached_amplitude = reached.at(role).strain_amplitude;
    const card::DataWindow window(material_card(s, role));
    if (const auto& range = window.strain_amplitude_range()) c.largest_tested_amplitude = range->second;
    out.push_back(std::move(c));
  }
  return out;
}

std::string beyond_tests_clause(const CardReading& c) {
  const std::optional<double> f = c.beyond_tests_factor();
  if (!f) return {};
  return c.role + " read at " + core::format_number(*f, 2) + "x its largest tested amplitude (" +
         core::format_number(c.reached_amplitude, 3) + " against " + core::format_number(*c.largest_tested_amplitude, 3) +
         ")";
}

void refuse_beyond_tests(const Scene& s, const std::vector<CardReading>& readings) {
  if (!s.life || s.life->beyond_tests != LifeSpec::BeyondTests::refuse) return;
  std::string beyond;
  for (const CardReading& c : readings)
    if (c.beyond_tests_factor()) beyond += (beyond.empty() ? "" : "; ") + ("card " + c.card + ": " + beyond_tests_clause(c));
  if (beyond.empty()) return;
  throw core::InputError("the segment drove a card beyond its tests (" + beyond + "), and [life] beyond_tests = "
                         "\"refuse\" refuses such a life: \"hold\" holds the damage at the drivers the tests reached, "
                         "\"extrapolate\" reads the damage law beyond them (docs/fatigue.md §8)",
                         s.path, 0, 0, "life.beyond_tests");
}

void mark_lives_beyond_tests(const std::vector<CardReading>& readings, fatigue::LifeReport& report) {
  for (fatigue::ModeLife& m : report.modes) {
    const char* role = m.mode == fatigue::Mode::radial_crack ? "bottom" : "cushion";
    for (const CardReading& c : readings)
      if (c.role == role && c.beyond_tests_factor()) {
        m.beyond_tests = beyond_tests_clause(c);
        m.significant_digits = fatigue::kDigitsBeyondTests;
      }
  }
}

}  // namespace detail
}  // namespace fitlib::scene
