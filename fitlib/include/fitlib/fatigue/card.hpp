#pragma once
// The fatigue card (schema fitlib.fatigue-card/1, docs/fatigue.md §4): the life constants of
// (6.31) per failure mode, their reference temperature, and optionally Gerbert's cord-break law
// (3.6)/(3.7). A bundled default with Report I's printed constants is datasets/cards/
// fatigue-fritzson-1988.json; default_card() returns the same values.
#include <array>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/core/fidelity.hpp"

namespace fitlib::fatigue {

enum class Mode { radial_crack = 1, separation = 2 };
const char* to_string(Mode mode);  // "radial_crack", "separation"
std::optional<Mode> mode_from_string(const std::string& text);  // the inverse; nullopt for other text

// The scatter of the observed lives about a mode's law: log10 N_obs − log10 N_law is normal with
// mean 0 and standard deviation sigma_log10 (a log-normal life whose median is the law's;
// docs/decisions.md "Life as a distribution: log-normal scatter about the law"), estimated by
// life-fit with `dof` degrees of freedom (cases − free constants).
struct LifeScatter {
  std::string distribution = "lognormal";  // the only one read (the card's key says which)
  double sigma_log10 = 0.0;
  int dof = 0;
};

// Covariance of the constants (ln σ0, n, b_per_C) in that order, as life-fit estimates it
// (s²(JᵀJ)⁻¹); a held constant's row and column are zero.
using LawCovariance = std::array<std::array<double, 3>, 3>;

// N = [Σ (σ_e,i/σ0)ⁿ]⁻¹ · 2^(−b(T − T_ref)) (6.31), N in load cycles (belt revolutions).
struct LifeLaw {
  double sigma0_MPa = 1.0;
  double n = 1.0;
  double b_per_C = 0.0;
  // The level of the stresses the constants were fitted to ([life] fidelity; absent = not stated).
  // The levels' stresses differ by orders of magnitude in σⁿ, so constants read at another level
  // give a life off their scale (docs/fatigue.md §4).
  std::optional<core::Fidelity> stress_fidelity;
  std::optional<LifeScatter> scatter = std::nullopt;  // optional in the card (docs/fatigue.md §4)
  std::optional<LawCovariance> covariance = std::nullopt;  // optional in the card
};

// Gerbert's cord break: σ_A = σ_a/(1 − σ_m/σ_U) (3.6), N = 10^(a − b σ_A) 2^(−b_T ΔT) (3.7),
// with σ = F/A_cord from the belt force over the cycle.
struct CordBreakLaw {
  double a = 0.0;
  double b_per_MPa = 0.0;
  double ultimate_MPa = 0.0;      // σ_U
  double cord_area_mm2 = 0.0;     // A_cord
  double b_T_per_C = 0.1;         // Gerbert's 10 °C halving
};

// The constants of both modes for the stresses of one level (docs/fatigue.md §4 "One life scale for
// every level"): the bundled card's beam and elastic entries are fitted by fitcli life-fit to the
// complete level's lives of a calibration set of drives (scripts/calibrate-levels.sh).
struct LevelLaws {
  LifeLaw radial_crack;
  LifeLaw separation;
  const LifeLaw& law(Mode m) const { return m == Mode::radial_crack ? radial_crack : separation; }
  LifeLaw& law(Mode m) { return m == Mode::radial_crack ? radial_crack : separation; }
};

struct FatigueCard {
  static constexpr const char* kSchema = "fitlib.fatigue-card/1";
  std::string name;
  double reference_temperature_C = 80.0;  // T_ref of ΔT in (6.31) ([UNCLEAR], docs/decisions.md)
  LifeLaw radial_crack{104.218, 4.423, 0.02897, core::Fidelity::complete};
  LifeLaw separation{4.21028, 11.69, 0.1466, core::Fidelity::complete};
  double crack_sweep_deg = 25.0;  // mode 1 crack directions ±sweep from radial
  std::optional<CordBreakLaw> cord_break;
  // Optional (JSON "levels"): constants per stress level for the levels `modes` were not fitted at;
  // each law's stress_fidelity is its key.
  std::map<core::Fidelity, LevelLaws> levels;
  nlohmann::json provenance = nlohmann::json::object();

  const LifeLaw& law(Mode m) const { return m == Mode::radial_crack ? radial_crack : separation; }
  LifeLaw& law(Mode m) { return m == Mode::radial_crack ? radial_crack : separation; }
};

// The bundled card datasets/cards/fatigue-fritzson-1988.json (its text built in at configure time):
// Report I's printed constants (docs/fatigue.md §4) at the project's reference temperature, fitted
// to the complete model's stresses (stress_fidelity "complete"), and the beam and elastic levels'
// calibrated constants ("levels").
FatigueCard default_card();

// The card whose modes are the constants for stresses of `fidelity`: per mode, its own law when
// that was fitted at `fidelity` (or does not say), else the `levels` entry of `fidelity` when the
// card has one (keeping the mode's scatter and covariance where the entry states none), else its
// own law (stress_fidelity_warning then says so). `levels` is emptied.
FatigueCard card_at_level(const FatigueCard& card, core::Fidelity fidelity);

// The warning for a life whose stresses come from `fidelity` read against constants fitted at
// another level ("" when every mode's constants are of that level or do not state theirs).
std::string stress_fidelity_warning(const FatigueCard& card, core::Fidelity fidelity);

nlohmann::json card_to_json(const FatigueCard& card);
// InputError naming `source` and the key path (e.g. modes.separation.n) for a missing key, a
// wrong type, a value out of range or an unknown key.
FatigueCard card_from_json(const nlohmann::json& j, const std::string& source);
FatigueCard load_card(const std::string& path);
void save_card(const std::string& path, const FatigueCard& card);

}  // namespace fitlib::fatigue
