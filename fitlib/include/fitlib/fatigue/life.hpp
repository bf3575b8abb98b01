#pragma once
// Fatigue life from stress histories at monitored points (Report I §6.4, docs/fatigue.md):
// crack-plane effective stress, the four-step peaks of the last load cycle, (6.31) per failure
// mode with the design point = the point of largest Σ(σ_e,i/σ0)ⁿ, Miner's rule over the pulleys,
// Gerbert's cord break (3.6)/(3.7) when the card has it, governing mode = shortest life.
//
// The input is plain data so that any stress source feeds it: the segment FE, the beam level
// (beam_section.hpp) or a user's own FE results.
#include <limits>
#include <optional>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/core/material_role.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/peaks.hpp"

namespace fitlib::fatigue {

// Material role of a monitored point (core::MaterialRole, the segment's): `bottom` points are
// checked for radial cracks (mode 1), `cushion` points for separation (mode 2).
using Role = core::MaterialRole;

struct StressSample {
  double t_s = 0.0;
  double s11_MPa = 0.0;  // radial
  double s22_MPa = 0.0;  // longitudinal
  double s12_MPa = 0.0;
  // Logarithmic strain in the same frame (e12 the tensor shear), for the output only: the segment
  // levels give it, the beam level and stress-only files leave NaN.
  double e11 = NAN, e22 = NAN, e12 = NAN;
};

struct PointHistory {
  std::string name;
  Role role = Role::bottom;
  double x_mm = 0.0, y_mm = 0.0;  // position in the segment (cord line y = 0, belt below)
  // A scanned FE point: its element, and the point's index in the element's rule (−1: a surface
  // node interpolated from its elements); element −1 for a named point.
  int element = -1, integration_point = -1;
  std::vector<StressSample> samples;  // increasing time
};

// One pulley's part of the load cycle (Miner's rule sums the damage of the parts).
struct CycleShare {
  std::string name;
  double t_begin_s = 0.0, t_end_s = 0.0;  // within one cycle, [begin, end)
};

struct LifeConditions {
  double temperature_C = 20.0;
  double cycle_time_s = 0.0;     // one load cycle; only the last one is evaluated (0: all samples)
  double cycles_per_hour = 0.0;  // belt speed / belt length · 3600 (0: no hours)
  std::vector<CycleShare> pulleys;
  std::vector<double> cord_force_N;  // belt force over the cycle, for the cord-break law
  PeakOptions peaks;
};

struct Peak {
  double t_s = 0.0;
  double stress_MPa = 0.0;
  std::string pulley;  // the share it falls in ("" when none does)
};

struct ShareDamage {
  std::string name;
  double damage_per_cycle = 0.0;  // Miner: 1/N = Σ over shares
};

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

struct ModeLife {
  Mode mode = Mode::radial_crack;
  std::string design_point;
  double x_mm = 0.0, y_mm = 0.0;
  int element = -1, integration_point = -1;  // the design point's, when a scan found it
  int points_evaluated = 0;                  // the mode's candidate points
  std::vector<Peak> peaks;
  double sum_terms = 0.0;           // Σ(σ_e,i/σ0)ⁿ at the design point
  double temperature_factor = 1.0;  // 2^(−bΔT)
  double life_cycles = kUnbounded;  // kUnbounded: no significant peak
  double life_h = kUnbounded;
  std::vector<ShareDamage> shares;
  std::vector<double> t_s, effective_stress_MPa;  // σ_e history of the design point (last cycle)
  // The largest peak's share of Σ(σ_e/σ0)ⁿ and how many samples carry it: the contiguous samples
  // around it whose own term is at least half the peak's (σ_e ≥ 2^(−1/n) σ_peak).
  double dominant_peak_share = 0.0;
  int dominant_peak_samples = 0;
  double largest_peak_over_sigma0 = 0.0;  // the largest peak's σ_e/σ0
  // Set by the caller when the stresses came from a card read beyond its tests ("cushion read at 13x
  // its largest tested amplitude"): life_table prints the life with kDigitsBeyondTests significant
  // digits and the clause, life_to_json adds "beyond_tests" and "extrapolated": true.
  std::string beyond_tests;
  int significant_digits = 4;
};

// Significant digits of a life read beyond its cards' tests (docs/decisions.md "Life: one policy for a
// card driven beyond its tests"): the damage treatment alone moves such a life by 2-4x.
constexpr int kDigitsBeyondTests = 2;

// A life dominated (> 90 % of the sum) by one peak that fewer than 3 samples carry: the increments
// may have missed its top, so the life can be off by the life exponent (docs/segment.md "The driver
// exit's peel transient").
bool peak_under_resolved(const ModeLife& m);

// Below this many load cycles (a minute of a 3000 rpm drive) a life says "fails at once": the
// power law (6.31) was fitted to belts that ran for hours (docs/decisions.md "Life: a life below
// 1000 cycles is a warning, not a number to read").
constexpr double kShortestReadableLife_cycles = 1e3;
// Above this many load cycles a life says "no fatigue failure in this mode" (a runout): (6.31) was
// fitted to belts that lived 1–2000 h (about 1e4–1e8 cycles; Report III: real drives live 10–100×
// longer), and a power law with n up to 11.7 reaches 1e193 cycles at no load (docs/decisions.md
// "Life: a life beyond 1e12 cycles is a runout, not a number to read").
constexpr double kLongestReadableLife_cycles = 1e12;

struct CordBreakLife {
  double mean_MPa = 0.0, amplitude_MPa = 0.0, equivalent_amplitude_MPa = 0.0;
  double life_cycles = kUnbounded, life_h = kUnbounded;
};

struct LifeReport {
  std::vector<ModeLife> modes;  // those with monitored points, in mode order
  std::optional<CordBreakLife> cord_break;
  std::string governing = "none";  // radial_crack | separation | cord_break | none (all unbounded)
  double life_cycles = kUnbounded, life_h = kUnbounded;
};

// N for the peaks of one point: [Σ(σ_i/σ0)ⁿ]⁻¹ 2^(−b(T − T_ref)) (6.31).
double sum_terms(const std::vector<double>& peaks_MPa, const LifeLaw& law);
double temperature_factor(const LifeLaw& law, double temperature_C, double reference_C);

// σ_e history of a point on its mode's crack plane(s): worst over ±sweep for bottom points,
// longitudinal crack for cushion points.
std::vector<double> effective_stress_history(const PointHistory& p, double crack_sweep_deg);

// Significant peaks (MPa) of one point over the last cycle. They do not depend on the life
// constants, which is why observed lives can be stored as peaks (life_fit.hpp).
std::vector<double> cycle_peaks_MPa(const PointHistory& p, double crack_sweep_deg,
                                    const LifeConditions& conditions);

// The life report. InputError for a point without samples in the last cycle or decreasing times;
// NumericalError naming point and time for non-finite stresses.
LifeReport evaluate_life(const std::vector<PointHistory>& points, const FatigueCard& card,
                         const LifeConditions& conditions);

// Cord break (3.6)/(3.7) from the belt force over the cycle.
CordBreakLife cord_break_life(const std::vector<double>& force_N, const CordBreakLaw& law,
                              double temperature_C, double reference_C, double cycles_per_hour);

// Human table: one line per mode (life in cycles and hours, design point, peaks, Σ terms), the
// cord break when evaluated, and the governing mode; "unbounded" where there is no peak.
std::string life_table(const LifeReport& report);

// JSON of the report; unbounded lives are written as null with "unbounded": true. With
// `effective_stress_history` each mode also holds its design point's σ_e over the last cycle
// ("effective_stress": {"t_s": [...], "MPa": [...]}), the curve its peaks were counted on.
nlohmann::json life_to_json(const LifeReport& report, bool effective_stress_history = false);

// One warning per mode whose finite life is below kShortestReadableLife_cycles or above
// kLongestReadableLife_cycles, and, where the
// points carry history (the complete level's glassy transients), per mode whose peak is under-
// resolved (peak_under_resolved: the elastic level's peaks at the planned steps move N2 by ≤ 8 %
// with 0.1 mm sampling, docs/segment.md "The driver exit's peel transient").
std::vector<std::string> life_warnings(const LifeReport& report, bool points_have_history = false);

}  // namespace fitlib::fatigue
