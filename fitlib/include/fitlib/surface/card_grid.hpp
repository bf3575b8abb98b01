#pragma once
// Modulus surfaces from fitted cards: a card evaluated over a grid of (strain amplitude,
// frequency, temperature) as tabular input for FE codes, and a Bezier surface fitted to that grid.
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/surface/fit.hpp"
#include "fitlib/surface/surface.hpp"

namespace fitlib::surface {

struct CardGridRequest {
  model::TestMode mode = model::TestMode::shear;
  std::string orientation;
  std::vector<double> frequency_Hz;      // required, positive
  std::vector<double> temperature_C;     // empty: the card's reference temperature (no axis)
  std::vector<double> strain_amplitude;  // empty: the small-amplitude limit (no axis)
};

struct ModulusGridRow {
  double strain_amplitude = 0.0, frequency_Hz = 0.0, temperature_C = 0.0;
  double storage_MPa = 0.0, loss_MPa = 0.0, mean_modulus_MPa = 0.0;
};

struct ModulusGrid {
  CardGridRequest request;
  std::string card_name, model_kind;
  std::vector<ModulusGridRow> rows;  // amplitude slowest, then frequency, temperature fastest
};

// Work cap (README "Work caps"): points of one grid (amplitudes × frequencies × temperatures).
// Measured: 10^7 points of a Prony card took 47 s, 1.9 GB and wrote 733 MB (4.7 µs and 73 bytes a
// point); the cap keeps a grid near 5 s. Above it evaluate_card_grid refuses before any work:
// InputError at key "grid points" with the count and the estimated time.
constexpr double kMaxCardGridPoints = 1e6;
constexpr double kCardGridPointCostS = 4.7e-6;

ModulusGrid evaluate_card_grid(const card::Card& card, const CardGridRequest& request);

// CSV with columns strain_amplitude, frequency_Hz, temperature_C (empty when the card's reference
// temperature was used), storage_MPa, loss_MPa, tan_delta, mean_modulus_MPa.
std::string modulus_grid_csv(const ModulusGrid& grid);

// The grid as measured points of one quantity ("storage", "loss", "tan_delta" or "mean") over
// its axes (Report V's order, those with values given): what surface_from_grid fits.
SampleSet grid_samples(const ModulusGrid& grid, const std::string& quantity);

// Fits a surface of one quantity ("storage", "loss", "tan_delta" or "mean") over the grid's axes
// in Report V's order (strain_amplitude, frequency_Hz, temperature_C; only axes with values given).
// `degrees` (optional, one per axis present) overrides the default levels - 1 (at most kMaxDegree).
// The surface describes log10 of the quantity when every grid value is positive (linear otherwise).
Surface surface_from_grid(const ModulusGrid& grid, const std::string& quantity,
                          const std::vector<int>& degrees = {});

}  // namespace fitlib::surface
