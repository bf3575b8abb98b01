#pragma once
// Master curves from raw isotherms (time–temperature superposition): free per-isotherm shifts
// log10 a_T found model-free from the overlap of adjacent isotherms, WLF and Arrhenius laws fitted
// to those shifts, and an optional joint refinement of the shifts with a model (docs/fitting.md,
// "Master curves from raw isotherms").
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::fit {

// Vertical shift of each isotherm: none; entropic b_T = T_ref/T (kelvin); or fitted per pair
// (the log offset of the neighbour that minimises the mismatch, same for E′ and E″).
enum class VerticalShift { none, entropic, fitted };

struct MasterCurveOptions {
  // Reference temperature, °C. NaN: the middle isotherm's temperature. Shifts are found relative
  // to the isotherm nearest T_ref, then re-referenced so that log a_T(T_ref) = 0 (linear
  // interpolation of the shifts between the bracketing isotherms).
  double reference_C = std::numeric_limits<double>::quiet_NaN();
  // Weight of the log E″ mismatch against log E′. Default 0: E′ only, as pyvisco and instrument
  // software shift. E″ helps where E′ is flat (plateaus) for data that superpose; on data that
  // are not Kramers–Kronig consistent (pyvisco's) E″ contradicts E′ (docs/fitting.md).
  double loss_weight = 0.0;
  // Search bracket for the shift between two adjacent isotherms, decades.
  double max_pair_shift_decades = 10.0;
  // A warmer isotherm never gets a larger a_T than its colder neighbour (thermorheologically
  // simple material); false searches both signs.
  bool monotone = true;
  // Points of the local power law (log-log line) that continues an isotherm beyond its ends.
  int extrapolation_points = 3;
  // A point beyond the neighbour's frequency range (compared with the power law) counts with
  // weight exp(−distance / taper_decades): it keeps the mismatch continuous in the shift and
  // bridges isotherms that do not overlap, while overlapping points dominate.
  double taper_decades = 0.25;
  // Sets whose mean temperatures differ by less than this are one isotherm (duplicates); rows
  // without a set are grouped by temperature with the same tolerance.
  double same_temperature_C = 0.5;
  VerticalShift vertical = VerticalShift::none;
};

struct IsothermShift {
  std::string set;            // set label; "a+b" when duplicate temperatures were merged
  double temperature_C = 0.0; // mean measured temperature of its rows
  double log10_aT = 0.0;      // horizontal shift: reduced frequency = f · a_T
  double log10_bT = 0.0;      // vertical: reduced moduli = E · b_T
  // Against the colder neighbour at the chosen shift (NaN for the coldest isotherm): rms of the
  // weighted log mismatch (decades) and the points that fall inside the neighbour's range.
  double pair_rms_decades = std::numeric_limits<double>::quiet_NaN();
  int pair_overlap_points = 0;
  std::vector<int> rows;      // indices into the raw table
};

// log10 a_T = −C1 (T − T_ref) / (C2 + T − T_ref).
struct WlfFit {
  double C1 = std::numeric_limits<double>::quiet_NaN();
  double C2_K = std::numeric_limits<double>::quiet_NaN();
  double rms_decades = std::numeric_limits<double>::quiet_NaN();
};
// log10 a_T = E_a / (R ln 10) · (1/T − 1/T_ref), T in kelvin.
struct ArrheniusFit {
  double activation_energy_kJ_mol = std::numeric_limits<double>::quiet_NaN();
  double rms_decades = std::numeric_limits<double>::quiet_NaN();
};

struct MasterCurve {
  double reference_C = 0.0;
  std::vector<IsothermShift> isotherms;  // coldest first
  // The raw rows shifted: frequency × a_T, moduli × b_T, temperature = reference_C; sorted by
  // reduced frequency; sources and sha256 of the raw table.
  data::DynamicTestTable master;
  WlfFit wlf;              // NaN with fewer than 3 isotherms
  ArrheniusFit arrhenius;  // NaN with fewer than 2 isotherms
  std::vector<std::string> messages;
};

// Groups `raw` into isotherms (by `set`, or by temperature when no row has a set), orders them
// by temperature and finds their shifts (pairwise, see docs). Throws core::InputError for rows
// without a temperature and for an isotherm with a single frequency when there are several.
MasterCurve build_master_curve(const data::DynamicTestTable& raw, const MasterCurveOptions& options = {});

// The same model-free shifts for relaxation isotherms: each E(t) is matched as a storage curve at
// f = 1/(2π t) (E(t) rises with 1/t as E′ does with f, and t/a_T = 1/(2π f a_T)), so the shifts
// read as those of frequency data. `master` is left empty: the caller shifts the relaxation rows
// (shift_relaxation_table).
MasterCurve build_relaxation_master_curve(const data::RelaxationTable& raw, MasterCurveOptions options = {});

// The card's temperature law on the measured isotherms: per isotherm (temperatures within 0.5 °C
// are one) and modulus, the relative errors of `model` at the rows' own temperatures; one warning
// when any isotherm passes the fit's thresholds, naming how many and the worst (docs/fitting.md
// "Quality verdict"). The fit's own figures are on the shifted master table.
QualityVerdict measured_isotherm_verdict(const model::Model& model, const std::vector<double>& p,
                                         const data::DynamicTestTable& measured);
QualityVerdict measured_isotherm_verdict(const model::Model& model, const std::vector<double>& p,
                                         const data::RelaxationTable& measured);

// Applies new shifts to the curve (e.g. after the joint refinement): master table and WLF /
// Arrhenius fits are rebuilt from `raw`.
void apply_shifts(MasterCurve& curve, const data::DynamicTestTable& raw, const std::vector<double>& log10_aT);

// WLF and Arrhenius fits of (T, log a_T) points. `C1_max`, `C2_max_K`: the WLF fit is the best one
// with C1 and C2 at most these (a card's bounds, docs/fitting.md "Round trip at fit time"); the
// default leaves them free.
WlfFit fit_wlf(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT, double reference_C,
               double C1_max = std::numeric_limits<double>::infinity(),
               double C2_max_K = std::numeric_limits<double>::infinity());
ArrheniusFit fit_arrhenius(const std::vector<double>& temperatures_C, const std::vector<double>& log10_aT,
                           double reference_C);

// A model on raw isotherm rows: `inner` (no temperature law) evaluated at the reduced frequency
// f · 10^{log_aT_k}, where k is the isotherm whose temperature is nearest the row's
// temperature_C (within tolerance_C, else core::InputError): TestCondition has no set field, so
// the measured temperature is the key. Parameters: inner's, then log_aT_0 … log_aT_{n−1}
// (decades, coldest first, group "shift"). d/d log_aT by central differences in log f.
model::ModelPtr make_isotherm_shift_model(model::ModelPtr inner, std::vector<double> isotherm_temperatures_C,
                                          double tolerance_C);

struct MasterFit {
  MasterCurve curve;         // final shifts (refined when refine_shifts)
  FitResult master;          // `model` fitted to the master table of the pairwise shifts
  std::optional<FitResult> joint;  // model and shifts fitted together on the raw rows
  std::vector<double> pairwise_log10_aT;  // the shifts before refinement
};

// build_master_curve, then fit(model, master table); with refine_shifts, every shift but the
// anchor's (the isotherm nearest T_ref, held) is then fitted together with the model's
// parameters on the raw rows (vertical factors held), starting from the master fit.
MasterFit fit_master_curve(const model::ModelPtr& model, const data::DynamicTestTable& raw,
                           const MasterCurveOptions& curve_options, const FitOptions& fit_options,
                           bool refine_shifts);

// The model of `result` (a fit at the reference temperature, law none) with temperature_law wlf
// at curve.reference_C and C1, C2 of the shift fit appended as fixed parameters: a card that
// carries the master curve's temperature dependence.
FitResult with_wlf_from_shifts(const FitResult& result, const MasterCurve& curve);

// Text table (T, log a_T, log b_T, pair rms, overlap, WLF/Arrhenius lines) and CSV
// (`T_C,log10_aT,log10_bT,set`, with `#` comment lines for the law fits).
std::string format_shift_table(const MasterCurve& curve);
std::string shift_table_csv(const MasterCurve& curve);

}  // namespace fitlib::fit
