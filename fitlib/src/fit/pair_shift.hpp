#pragma once
// Private: the model-free shift between two adjacent isotherms (docs/fitting.md, "Master curves
// from raw isotherms").
#include "isotherms.hpp"

namespace fitlib::fit::detail {

constexpr double kGridStep_decades = 0.05;  // pair-shift scan before Brent

struct PairShift {
  double shift = 0.0, vertical = 0.0, rms = 0.0;
  int overlap = 0;
};

// The shift d (decades) of warm isotherm b onto cold isotherm a that minimises their weighted
// log mismatch: a grid scan over the bracket, then Brent's method in the best grid cell.
PairShift best_pair_shift(const Isotherm& a, const Isotherm& b, const MasterCurveOptions& o);

}  // namespace fitlib::fit::detail
