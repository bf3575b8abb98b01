// The load cycle as a periodic, interpolated history for the segment solver.
#include "fitlib/belt/load_history.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"

namespace fitlib::belt {
namespace {

LoadState mix(const LoadState& a, const LoadState& b, double w) {
  auto lerp = [w](double x, double y) { return x + w * (y - x); };
  return {lerp(a.s_mm, b.s_mm),        lerp(a.t_s, b.t_s),         lerp(a.F_N, b.F_N),
          lerp(a.strain, b.strain),    lerp(a.K_1_mm, b.K_1_mm),   lerp(a.p_MPa, b.p_MPa),
          lerp(a.gamma_rad, b.gamma_rad), lerp(a.temperature_C, b.temperature_C),
          lerp(a.friction_used, b.friction_used), lerp(a.slide_mm_s, b.slide_mm_s)};
}

}  // namespace

LoadHistory::LoadHistory(const LoadCycle& cycle, const BeltSection& belt, double temperature_C)
    : length_mm_(cycle.cycle_length_mm), period_s_(cycle.cycle_time_s) {
  if (cycle.samples.empty() || !(length_mm_ > 0.0))
    throw core::InputError("load history: the load cycle has no samples or no length");
  if (!(belt.c_N > 0.0)) throw core::InputError("load history: the belt stiffness c must be > 0");
  for (const LoadSample& q : cycle.samples)
    samples_.push_back({q.s_mm, q.t_s, q.F_N, q.F_N / belt.c_N, q.K_1_mm, q.p_MPa, q.gamma_rad,
                        temperature_C, q.friction_used, q.slide_mm_s});
}

LoadHistory LoadHistory::shifted(double s_mm) const {
  LoadHistory out = *this;
  const double s = std::fmod(std::fmod(s_mm, length_mm_) + length_mm_, length_mm_);
  const double t = period_s_ > 0.0 ? s / length_mm_ * period_s_ : 0.0;
  out.samples_.clear();
  for (int pass = 0; pass < 2; ++pass)  // the samples from s on, then those before it a length on
    for (LoadState q : samples_) {
      if ((q.s_mm >= s) != (pass == 0)) continue;
      q.s_mm += pass == 0 ? -s : length_mm_ - s;
      q.t_s += pass == 0 ? -t : period_s_ - t;
      out.samples_.push_back(q);
    }
  return out;
}

LoadState LoadHistory::at_position(double s_mm) const {
  double s = std::fmod(s_mm, length_mm_);
  if (s < 0.0) s += length_mm_;
  // First sample beyond s; the segment before it (wrapping to the first sample one length on).
  const auto after = std::upper_bound(samples_.begin(), samples_.end(), s,
                                      [](double x, const LoadState& q) { return x < q.s_mm; });
  LoadState a = after == samples_.begin() ? samples_.back() : *(after - 1);
  LoadState b = after == samples_.end() ? samples_.front() : *after;
  if (after == samples_.begin()) a.s_mm -= length_mm_, a.t_s -= period_s_;
  if (after == samples_.end()) b.s_mm += length_mm_, b.t_s += period_s_;
  const double w = b.s_mm > a.s_mm ? (s - a.s_mm) / (b.s_mm - a.s_mm) : 0.0;
  LoadState out = mix(a, b, w);
  out.s_mm = s;
  return out;
}

LoadState LoadHistory::at_time(double t_s) const {
  if (!(period_s_ > 0.0))
    throw core::UsageError("load history: the belt does not move (no cycle time)");
  LoadState out = at_position(t_s / period_s_ * length_mm_);
  double t = std::fmod(t_s, period_s_);
  out.t_s = t < 0.0 ? t + period_s_ : t;
  return out;
}

}  // namespace fitlib::belt
