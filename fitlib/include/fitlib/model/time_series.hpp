#pragma once
// Time-domain building blocks shared by the linear models: a generalized Maxwell (Prony) series
// and a Kelvin chain (discrete retardation spectrum), each with an integrator that is exact for
// piecewise-linear input between samples.
#include <vector>

#include "fitlib/model/model.hpp"

namespace fitlib::model {

// M(t) = M_inf + Σ M_i exp(−t/τ_i). Moduli may be negative (e.g. the three-parameter solid with
// τ_ε < τ_T), times must be positive.
struct MaxwellSeries {
  double relaxed = 0.0;            // M_inf, MPa
  std::vector<double> moduli;      // M_i, MPa
  std::vector<double> times_s;     // τ_i, s

  double glassy() const;                        // M(0+)
  double relaxation(double t_s) const;          // M(t)
  // Stress for a strain history, exact for strain linear between samples, from rest.
  std::vector<double> stress(const StrainHistory& history) const;
  // Creep compliance J(t) under a unit stress step, by stress-controlled stepping on a
  // log-spaced grid (second order; `steps_per_decade` is the accuracy knob).
  double creep(double t_s, int steps_per_decade = 400) const;
};

// The three-parameter solid T + τ_T Ṫ = S(ε + τ_ε ε̇) (Sorge–Cammalleri Eq. 1; docs/model.md)
// as a Maxwell series: M∞ = S, M_1 = S(τ_ε/τ_T − 1), τ_1 = τ_T.
MaxwellSeries three_parameter_solid(double S, double tau_T_s, double tau_eps_s);

// J(t) = J_g + Σ L_i (1 − exp(−t/λ_i)).
struct KelvinSeries {
  double glassy_compliance = 0.0;  // J_g, 1/MPa
  std::vector<double> compliances; // L_i, 1/MPa
  std::vector<double> times_s;     // λ_i, s

  double creep(double t_s) const;
  // Stress for a strain history (strain-controlled; each step solves the linear Kelvin update
  // exactly for stress linear between samples), from rest.
  std::vector<double> stress(const StrainHistory& history) const;
  // Relaxation modulus after a unit strain step (a ramp of `rise_s` then hold).
  double relaxation(double t_s, int steps_per_decade = 400) const;
  // The same material as an exact Maxwell series (docs/model.md §"Kelvin to Maxwell"): the
  // relaxation times are the zeros of J_g + Σ L_i/(1 − λ_i/τ), one per Kelvin element; a term
  // below 1e-12 of the total compliance is left out (its zero is within round-off of its rate).
  // Throws core::UsageError unless J_g > 0, L_i > 0 and λ_i > 0.
  MaxwellSeries to_maxwell() const;
};

// Stress-strain steady state from a time integration: drives `model` with
// ε(t) = mean + amplitude·sin(ωt) for `cycles` cycles at `steps_per_cycle` and fits
// a + b·t + E′·ε_a sin ωt + E″·ε_a cos ωt over the last cycle (the linear part absorbs slow
// transients of long relaxation times). Returns storage and loss; `mean` = the fitted a / mean.
Moduli<double> steady_state_by_time_integration(const Model& model, const double* p,
                                                const TestCondition& c, int cycles = 60,
                                                int steps_per_cycle = 4000);

}  // namespace fitlib::model
