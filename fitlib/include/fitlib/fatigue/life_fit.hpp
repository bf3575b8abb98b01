#pragma once
// Fitting the life constants σ0, n, b of (6.31) per failure mode to observed belt lives
// (Report I §6.5.2; docs/fatigue.md §6): Ceres on log10-life residuals
//   r = log10 N_pred − log10 N_obs,  N_pred = [max_points Σ_i (σ_i/σ0)ⁿ]⁻¹ 2^(−b(T − T_ref)),
// the design point of each case re-chosen for the current n, with 95 % intervals from the
// Jacobian at the solution. Each mode is fitted to the cases that failed in that mode (as the
// thesis did: two separable problems). A runout (a test stopped without failure) bounds each mode's
// life from below: its residual is min(0, log10 N_pred − log10 N_obs), so it pulls only a law that
// predicts failure before the test stopped (docs/fatigue.md §6 "Runouts").
#include <optional>
#include <string>
#include <vector>

#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/life.hpp"

namespace fitlib::fatigue {

struct ObservedLife {
  std::string name;
  Mode mode = Mode::radial_crack;  // observed failure mode
  double temperature_C = 20.0;
  double observed_cycles = 0.0;
  // Significant peaks (MPa) of each monitored point of that mode, e.g. from evaluate_life.
  std::vector<std::vector<double>> point_peaks_MPa;
  std::optional<core::Fidelity> stress_fidelity;  // the level of the peaks (LifeLaw::stress_fidelity; absent: not stated)
  // A runout: the test stopped at observed_cycles without failing; `mode` names the mode whose
  // points the peaks are of (a runout test gives one case per mode).
  bool runout = false;
  int line = 0;  // first line in the CSV (messages)
};

// Observed-lives CSV (docs/fatigue.md §6): one row per case and monitored point, columns
//   case, failure_mode (radial_crack | separation), temperature_C,
//   observed_cycles  or  observed_h and cycles_per_h,  [point],  peaks_MPa ("σ1;σ2;…"),
//   [stress_fidelity] (beam | elastic | complete: the level the peaks were computed at),
//   [runout] (0 | 1: the test stopped without failing; its rows may list both modes' points)
// Rows of one case must agree on mode, temperature, life, level and runout (a runout's rows per
// mode), and the cases of one mode on their level (check_one_stress_fidelity). InputError naming
// file, line and column for anything else.
std::vector<ObservedLife> parse_observed_lives(const std::string& text, const std::string& source);
std::vector<ObservedLife> read_observed_lives(const std::string& path);

// One observed case from computed stress histories (segment, beam level, …): the peaks of every
// monitored point of `mode`, with the card's crack sweep and the conditions' peak options.
ObservedLife observed_life(const std::string& name, Mode mode, double observed_cycles,
                           const std::vector<PointHistory>& points, const FatigueCard& card,
                           const LifeConditions& conditions);

// Whether any monitored point of `mode` has a significant peak (observed_life would find one).
bool has_peaks(Mode mode, const std::vector<PointHistory>& points, const FatigueCard& card,
               const LifeConditions& conditions);

// InputError naming `source`, the line of the first case of a mode whose stresses come from
// another level than an earlier case's of that mode: one law is fitted per mode, and a fit
// across levels mixes stresses of different scales.
void check_one_stress_fidelity(const std::vector<ObservedLife>& cases, const std::string& source);

// The CSV parse_observed_lives reads (observed_cycles form, exact numbers: reads back equal).
std::string observed_lives_csv(const std::vector<ObservedLife>& cases);

struct ConstantEstimate {
  std::string name, unit;
  double value = 0.0;
  bool fixed = false;
  bool has_interval = false;
  double std_error = 0.0, ci95_low = 0.0, ci95_high = 0.0;
};

// The bounds of n in the fit; a fit that ends on one is not a result (LifeFitResult::rejected).
constexpr double kExponentMin = 0.1, kExponentMax = 100.0;

struct LifeFitOptions {
  double reference_temperature_C = 80.0;  // the card's T_ref
  LifeLaw start;              // start values
  bool fix_n = false;         // hold n at start.n (also automatic with one case)
  bool fix_b = false;         // hold b at start.b_per_C (also automatic with one temperature or < 3 cases)
};

struct LifeFitResult {
  Mode mode = Mode::radial_crack;
  LifeLaw law;
  std::vector<ConstantEstimate> constants;  // sigma0_MPa, n, b_per_C
  int cases = 0;    // failures in this mode
  int runouts = 0;  // runouts with points of this mode
  // Runouts the fitted law says fail before the test stopped, by more than the scatter warning's
  // factor: "name (predicted N, stopped at M)".
  std::vector<std::string> violated_runouts;
  double rms_log10_error = 0.0;  // over the failures and the runouts the law violates
  std::string note;  // why an interval or a constant is missing
  // Why the card keeps the start's law for this mode instead ("" = the fit is the card's): n at
  // a bound of [0.1, 100] means the lives do not fall with the stress as (6.31) needs (σ0 then
  // runs to 10¹⁰⁰ MPa or onto the stresses themselves), a result not to be written as a constant.
  std::string rejected;
};

// NumericalError when Ceres fails; InputError when no case failed in `mode`.
LifeFitResult fit_life_law(const std::vector<ObservedLife>& cases, Mode mode,
                           const LifeFitOptions& options);

// A fatigue card fitted to observed cases: `start` with the law of every mode that has cases
// replaced by its fit (T_ref and the crack sweep are the start's), the fits, and warnings for
// what a user should not read as a result: a mode no case failed in or whose fit put n at a bound
// (its start constants kept, LifeFitResult::rejected; NumericalError when no mode with cases was
// fitted), lives scattering around the fit by more than kScatterWarning_log10, n's or b's 95 % interval
// reaching zero, σ0's 95 %
// interval spanning more than a factor kSpreadWarning, as many free constants as cases (the fit
// passes through them all), a free n without an interval from cases whose largest peaks span
// less than a factor 1.25. provenance.life_fit records each fit.
struct LifeCardFit {
  FatigueCard card;
  std::vector<LifeFitResult> fits;  // one per mode with cases, in mode order
  std::vector<std::string> warnings;
};
constexpr double kScatterWarning_log10 = 0.5;  // a factor 3.2: beyond a fatigue test's usual 2–3
constexpr double kSpreadWarning = 10.0;
struct HeldConstants {
  bool n = false, b = false;  // hold at the start card's values (each also automatic, LifeFitOptions)
};
LifeCardFit fit_life_card(const std::vector<ObservedLife>& cases, const FatigueCard& start,
                          const HeldConstants& held = {});

// One fit as JSON: cases, runouts, rms_log10_error, note, constants (value, fixed, std_error, ci95).
nlohmann::json life_fit_json(const LifeFitResult& fit);

// log10 N_pred of one case under `law` (the design point chosen for law.n).
double predicted_log10_life(const ObservedLife& c, const LifeLaw& law, double reference_C);

// The runouts of `mode` that `law` says fail before their test stopped by more than a factor
// 10^slack_log10: "name (predicted N cycles, stopped at M)".
std::vector<std::string> violated_runouts(const std::vector<ObservedLife>& cases, Mode mode, const LifeLaw& law,
                                          double reference_C, double slack_log10);

}  // namespace fitlib::fatigue
