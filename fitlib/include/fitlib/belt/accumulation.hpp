#pragma once
// Strain accumulation under periodic tooth-like shear loading (Zupancic–Emri; docs/belt.md, "Zupancic–Emri").
//
// Each belt cycle loads a tooth with τ0 while it runs round a pulley (π/ω) and unloads it for the
// rest of the cycle; ξ = 2(κ + π)/ω with κ = l/R. With a discrete retardation spectrum
// J(t) = J_g + Σ L_i (1 − e^{−t/λ_i}), the strain left at the end of N cycles is Eq. (5). Its sum
// over cycles is geometric, so Γ(N, ω, κ) costs O(K), not O(N·K).
#include <string>
#include <vector>

#include "fitlib/model/time_series.hpp"

namespace fitlib::belt {

// The discrete retardation spectrum J_g, L_i (1/MPa), λ_i (s) is the model's Kelvin series
// (one source for the law; time_series.hpp).
using RetardationSpectrum = model::KelvinSeries;

// Validates (equal sizes, L ≥ 0, λ > 0); InputError naming `key` otherwise.
void validate(const RetardationSpectrum& s, const std::string& key = "spectrum");

// The five envelope shapes of the paper around log10 λ = 0 ("box", "gauss", "lorentzian", "ramp",
// "wedge"), sampled at `lines_per_decade` over log10 λ ∈ [−6, 6], scaled to Σ L_i = total.
// Shapes (docs/belt.md): box = 1 on |log λ| ≤ 4; gauss σ = 0.5 decade; lorentzian half-width 0.5
// decade; ramp rises linearly from log λ = −6 to 0 and stays constant; wedge falls linearly from
// log λ = −6 to 0 at +6. InputError (key `spectrum`) for an unknown name.
RetardationSpectrum spectrum_shape(const std::string& name, double total_L_1_MPa = 1.0,
                                   int lines_per_decade = 4, double J_g_1_MPa = 0.0);
std::vector<std::string> spectrum_shape_names();

// Accumulated strain at the end of N cycles, Eq. (5), closed form over n (O(K)).
double accumulated_strain(const RetardationSpectrum& s, double tau0_MPa, double N_cycles,
                          double omega_rad_s, double kappa);
// Eq. (5) summed term by term over n (O(N·K)): the baseline of the benchmark.
double accumulated_strain_direct_sum(const RetardationSpectrum& s, double tau0_MPa, long N_cycles,
                                     double omega_rad_s, double kappa);
// Strain γ(t) of the hereditary integral (2) integrated in time: the loading (1) is stepped
// through every loading and unloading phase with the exact exponential update of each Kelvin
// element; returns γ at the end of N cycles (t = Nξ). Independent of Eq. (5).
double accumulated_strain_time_integration(const RetardationSpectrum& s, double tau0_MPa,
                                           long N_cycles, double omega_rad_s, double kappa,
                                           int substeps_per_phase = 1);

// Smallest N ≤ N_max with Γ(N) ≥ strain_limit, or −1 when Γ stays below (Γ rises with N).
long critical_cycles(const RetardationSpectrum& s, double tau0_MPa, double omega_rad_s,
                     double kappa, double strain_limit, long N_max);

}  // namespace fitlib::belt
