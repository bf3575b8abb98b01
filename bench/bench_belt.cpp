// Belt benchmarks (plain main, prints its tables):
// 1. The load cycle of the reference drive (datasets/drives/ref-0500-heavy.toml values) with effect
//    sets from minimal to full: wall time per cycle and how far F, p, γ are from the full set
//    (accuracy versus time). Baseline: the minimal set, measured in the same run.
// 2. The Zupancic–Emri map Γ(N = 10⁴, ω) over 100 speeds: closed form O(K) against the direct sum of
//    Eq. (5) O(N·K); baseline: the direct sum.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fitlib/belt/accumulation.hpp"
#include "fitlib/belt/drive.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/belt/stiffness.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using Clock = std::chrono::steady_clock;

namespace {
using fitlib::core::kPi;

DriveCase reference_drive() {
  Pulley a{"driver", 50.0, PulleyRole::driver}, b{"driven", 50.0, PulleyRole::driven};
  DriveCase c;
  c.geometry = make_two_pulley_geometry(a, b, 300.0);
  c.span_tension_N = span_tensions(c.geometry, {30.0, TensionRule::initial, 600.0});
  c.friction = 0.5;
  c.belt_speed_mm_s = 3000.0 * 2 * kPi / 60 * 50.0;
  c.belt.c_N = cord_stiffness_N(80.0);
  c.belt.EI_Nmm2 = bending_stiffness_Nmm2(80.0);
  c.belt.k1_MPa = radial_stiffness_MPa(c.belt.wedge_half_angle_rad, axial_modulus_MPa(80.0),
                                       c.belt.height_mm, c.belt.width_mm);
  return c;
}

template <typename F>
double seconds_per_call(F f, double min_total_s = 0.2) {
  int n = 1;
  for (;;) {
    const auto t0 = Clock::now();
    for (int k = 0; k < n; ++k) f();
    const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
    if (dt >= min_total_s) return dt / n;
    n *= 2;
  }
}

// Largest pointwise difference relative to the largest value of the reference, on the reference's s grid.
double max_rel(const LoadCycle& ref, const LoadCycle& x, double LoadSample::*field) {
  double scale = 0, diff = 0;
  for (const auto& q : ref.samples) {
    auto it = std::lower_bound(x.samples.begin(), x.samples.end(), q.s_mm,
                               [](const LoadSample& a, double v) { return a.s_mm < v; });
    const LoadSample& y = it == x.samples.end() ? x.samples.back() : *it;
    scale = std::max(scale, std::abs(q.*field));
    diff = std::max(diff, std::abs(q.*field - y.*field));
  }
  return scale > 0 ? diff / scale : 0.0;
}
}  // namespace

int main() {
  const DriveCase drive = reference_drive();
  struct Set { const char* name; LoadCycleEffects fx; };
  const std::vector<Set> sets{
      {"minimal (closed-form arcs only)", {false, false, false, false}},
      {"+ inertia", {false, true, false, false}},
      {"+ inertia + bending zones", {true, true, false, false}},
      {"+ driver exit ramp", {true, true, false, true}},
      {"full (+ ODE arcs)", {true, true, true, true}},
  };
  std::vector<LoadCycle> cycles;
  std::vector<double> times;
  for (const auto& s : sets) {
    LoadCycleOptions o;
    o.effects = s.fx;
    cycles.push_back(compute_load_cycle(drive, o));
    times.push_back(seconds_per_call([&] { compute_load_cycle(drive, o); }));
  }
  std::printf("Load cycle, reference drive 0.500 in cogged belt, 2 x 100 mm, 30 N·m, 3000 rpm, 80 °C\n");
  std::printf("%-34s %12s %10s %12s %12s %12s\n", "effects", "time [us]", "x minimal", "dF/F_full", "dp/p_full", "dgamma/g_full");
  for (std::size_t k = 0; k < sets.size(); ++k)
    std::printf("%-34s %12.2f %10.2f %12.4f %12.4f %12.4f\n", sets[k].name, times[k] * 1e6, times[k] / times[0],
                max_rel(cycles.back(), cycles[k], &LoadSample::F_N), max_rel(cycles.back(), cycles[k], &LoadSample::p_MPa),
                max_rel(cycles.back(), cycles[k], &LoadSample::gamma_rad));
  std::printf("sliding arcs [deg]: closed form driven %.2f / driver %.2f; ODE driven %.2f / driver %.2f\n\n",
              cycles[3].pulleys[0].sliding_rad * 180 / kPi, cycles[3].pulleys[1].sliding_rad * 180 / kPi,
              cycles[4].pulleys[0].sliding_rad * 180 / kPi, cycles[4].pulleys[1].sliding_rad * 180 / kPi);

  // Γ map: N = 10⁴, 100 speeds log-spaced over 1 … 10⁴ 1/s, Gauss spectrum (97 lines), κ = π.
  const auto spectrum = spectrum_shape("gauss", 1.0, 8);
  std::vector<double> omega;
  for (int i = 0; i < 100; ++i) omega.push_back(std::pow(10.0, 4.0 * i / 99.0));
  const long N = 10000;
  std::vector<double> closed(100), direct(100);
  const double t_closed = seconds_per_call([&] {
    for (int i = 0; i < 100; ++i) closed[i] = accumulated_strain(spectrum, 1.0, N, omega[i], kPi);
  });
  const double t_direct = seconds_per_call([&] {
    for (int i = 0; i < 100; ++i) direct[i] = accumulated_strain_direct_sum(spectrum, 1.0, N, omega[i], kPi);
  }, 0.5);
  double worst = 0;
  for (int i = 0; i < 100; ++i) worst = std::max(worst, std::abs(closed[i] / direct[i] - 1));
  std::printf("Zupancic-Emri map, N = 1e4, 100 speeds, K = %zu lines\n", spectrum.compliances.size());
  std::printf("%-30s %14s %10s\n", "method", "time [ms]", "speed-up");
  std::printf("%-30s %14.4f %10.1f\n", "direct sum of Eq. (5)", t_direct * 1e3, 1.0);
  std::printf("%-30s %14.4f %10.1f\n", "closed form (geometric)", t_closed * 1e3, t_direct / t_closed);
  std::printf("max relative difference closed vs direct: %.2e\n", worst);
  return 0;
}
