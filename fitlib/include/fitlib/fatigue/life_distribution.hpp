#pragma once
// Life as a distribution (docs/fatigue.md §9): per mode, the law's life (6.31) is the median of a
// log-normal life, log10 N ~ Normal(log10 N_law, s²) with s the card's scatter (life-fit's residual
// standard deviation of log10 life; docs/decisions.md "Life as a distribution: log-normal scatter
// about the law"). B_p, the life by which p % of the belts have failed, is
//   log10 B_p = log10 N_law + z_p s          (z_10 = −1.2816, z_50 = 0),
// and its 90 % interval carries the constants' uncertainty (their covariance C over (ln σ0, n, b))
// to first order: log10 B_p ± t_0.95 √(gᵀ C g), g = ∂ log10 N/∂(ln σ0, n, b) at the design point.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/life.hpp"

namespace fitlib::fatigue {

struct BLife {
  double percent = 50.0;
  double cycles = 0.0, h = 0.0;
  bool has_hours = false;     // the conditions give cycles per hour
  bool has_interval = false;  // the card has the constants' covariance
  double low_cycles = 0.0, high_cycles = 0.0, low_h = 0.0, high_h = 0.0;  // 90 % interval
  // [life] uncertainty = "cards": the 90 % interval over the lives run on card draws
  bool has_cards_interval = false;
  double cards_low_cycles = 0.0, cards_high_cycles = 0.0, cards_low_h = 0.0, cards_high_h = 0.0;
  // [life] uncertainty = "constants+cards": the 90 % interval of both sources as one distribution
  bool has_combined_interval = false;
  double combined_low_cycles = 0.0, combined_high_cycles = 0.0, combined_low_h = 0.0, combined_high_h = 0.0;
};

// How the cards' interval was made (docs/thermal.md §7): draws run, draws that failed (their run
// stopped: a thermal runaway, a drawn card without a material at the temperature), the seed, and
// the draws' median life against the deterministic one.
struct CardsSampling {
  int samples = 0, failed = 0;
  std::uint64_t seed = 0;
  std::string first_failure;
  double median_cycles = 0.0;
};

struct ModeDistribution {
  Mode mode = Mode::radial_crack;
  double sigma_log10 = 0.0;        // the card's scatter of log10 life about the law
  int dof = 0;                     // its degrees of freedom
  double constants_sd_log10 = 0.0; // √(gᵀ C g): the law's own uncertainty in log10 N
  BLife b10, b50;
  std::optional<CardsSampling> cards;
};

// The cards' 90 % interval of B10 and B50 from the mode's lives on card draws: the 5th and 95th
// percentiles (linear between order statistics) of N_j 10^(z_p s); an infinite draw stays infinite.
void add_cards_interval(ModeDistribution& d, std::vector<double> draw_cycles, const CardsSampling& sampling);

// Both sources as one distribution (docs/thermal.md §7): log10 life = a draw's log10 N_j plus the
// constants' error sd·T (T Student t with the scatter's dof, as the constants' interval), so its
// distribution is the draws' empirical one convolved with the constants' scaled t:
//   F(x) = (1/J) Σ_j F_T((x − log10 N_j)/sd);
// the 90 % interval of B_p is its 5th and 95th percentiles times 10^(z_p s). Draws all equal give
// the constants' interval; sd = 0 (no covariance of the constants) gives the cards' interval.
// Call after add_cards_interval with the same draws.
void add_combined_interval(ModeDistribution& d, const std::vector<double>& draw_cycles);

// ∂ log10 N/∂(ln σ0, n, b) of (6.31) at one point's peaks and temperature offset dT = T − T_ref.
std::array<double, 3> log10_life_gradient(const std::vector<double>& peaks_MPa, const LifeLaw& law, double dT);

// The distribution of one mode's life (nullopt when it is unbounded or the law has no scatter).
std::optional<ModeDistribution> mode_distribution(const ModeLife& mode, const LifeLaw& law, double temperature_C,
                                                  double reference_C, double cycles_per_hour);

// Each finite mode of the report whose card law states a scatter, in the report's order.
std::vector<ModeDistribution> life_distribution(const LifeReport& report, const FatigueCard& card,
                                                const LifeConditions& conditions);

// One line per mode: "B10 … [low, high] h, B50 …"; a note for each finite mode without a scatter.
std::string life_distribution_table(const LifeReport& report, const std::vector<ModeDistribution>& d);
nlohmann::json life_distribution_json(const std::vector<ModeDistribution>& d);

}  // namespace fitlib::fatigue
