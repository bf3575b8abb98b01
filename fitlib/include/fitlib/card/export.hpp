#pragma once
// Writers of FE-solver material keywords from a card. A writer refuses (core::UsageError with a
// message saying why) what its format cannot hold: amplitude dependence, a model that is not an
// exact Prony series, negative relaxation weights, more terms than the solver accepts, a
// temperature law the solver lacks.
#include <limits>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"

namespace fitlib::card {

struct ExportOptions {
  // Poisson ratio of the instantaneous elastic response where the card has no bulk modulus.
  // Default 0.4995 ⇔ K ≈ 10³ G (docs/decisions.md, "exports: what each FE format receives").
  double poisson_ratio = kDefaultPoissonRatio;
  int material_id = 1;
  // Mass density in t/mm³ (consistent with MPa, mm, s; rubber ≈ 1.2e-9), LS-DYNA's RO. The card
  // holds none and RO = 0 stops an explicit LS-DYNA run, so the LS-DYNA export refuses without it.
  double density_t_per_mm3 = 0.0;
  // Write a card whose terms break the admissible window it records (fit.admissible) or whose
  // relaxed/instantaneous ratio is below kMinRelaxedRatio (docs/fitting.md "Admissible terms").
  bool allow_inadmissible = false;
  // Export the card at one temperature (°C; NaN: keep its law): the terms' times scaled by the
  // law's shift factor there and the moduli by its vertical factor, no temperature shift in the
  // deck. The route for laws the solver lacks (polynomial, Arrhenius, vertical shifts).
  double temperature_C = std::numeric_limits<double>::quiet_NaN();
};

// Smallest relaxed / instantaneous modulus an exported card may have (FE stability).
constexpr double kMinRelaxedRatio = 1e-3;

// Why the card's series terms are not admissible (empty when they are): terms outside the
// window its fit recorded, moduli above the ceiling, the relaxed modulus below its floor or
// below kMinRelaxedRatio of the instantaneous one.
std::string admissibility_problems(const Card& card);

// The formats export_card writes, in the order help texts list them.
const std::vector<std::string>& export_formats();

// format: one of export_formats().
std::string export_card(const Card& card, const std::string& format, const ExportOptions& options = {});

// Largest number of Prony terms each format accepts (0 = no limit known).
int max_prony_terms(const std::string& format);

}  // namespace fitlib::card
