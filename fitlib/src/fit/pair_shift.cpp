// Pairwise shifts: the weighted mismatch of two isotherms and its minimum over the shift.
#include "pair_shift.hpp"

#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>

namespace fitlib::fit::detail {
namespace {

constexpr int kBrentBits = 40;

// Weighted mismatch of warm isotherm b shifted by d decades against cold isotherm a (in a's raw
// log f: x_b + d), both ways; with a fitted vertical offset the weighted mean is removed.
PairShift pair_mismatch(const Isotherm& a, const Isotherm& b, double d, const MasterCurveOptions& o) {
  double sw = 0, swr = 0, swrr = 0;
  int overlap = 0;
  const bool loss = a.has_loss && b.has_loss && o.loss_weight > 0;
  auto add = [&](double r, double w) { sw += w, swr += w * r, swrr += w * r * r; };
  auto compare = [&](const Isotherm& from, const Isotherm& to, double offset, double sign) {
    for (std::size_t j = 0; j < from.storage.x.size(); ++j) {
      const double xq = from.storage.x[j] + offset;
      const double dist = to.storage.outside(xq);
      if (dist == 0.0) ++overlap;
      const double w = std::exp(-dist / o.taper_decades);
      add(sign * (from.storage.y[j] - to.storage.value(xq)), w);
      if (loss) add(sign * (from.loss.y[j] - to.loss.value(xq)), w * o.loss_weight);
    }
  };
  compare(b, a, d, 1.0);    // residual = b − a
  compare(a, b, -d, -1.0);  // residual = b − a as well
  PairShift p;
  p.shift = d;
  p.overlap = overlap;
  p.vertical = o.vertical == VerticalShift::fitted ? swr / sw : 0.0;
  p.rms = std::sqrt(std::max(0.0, swrr / sw - (o.vertical == VerticalShift::fitted ? p.vertical * p.vertical : 0.0)));
  return p;
}

}  // namespace

PairShift best_pair_shift(const Isotherm& a, const Isotherm& b, const MasterCurveOptions& o) {
  const double lo = -o.max_pair_shift_decades, hi = o.monotone ? 0.0 : o.max_pair_shift_decades;
  double best_d = hi, best = std::numeric_limits<double>::infinity();
  const int steps = static_cast<int>(std::ceil((hi - lo) / kGridStep_decades));
  for (int i = 0; i <= steps; ++i) {
    const double d = std::min(hi, lo + i * kGridStep_decades);
    const double r = pair_mismatch(a, b, d, o).rms;
    if (r < best) best = r, best_d = d;
  }
  const auto objective = [&](double d) { return pair_mismatch(a, b, d, o).rms; };
  const auto [d, r] = boost::math::tools::brent_find_minima(
      objective, std::max(lo, best_d - kGridStep_decades), std::min(hi, best_d + kGridStep_decades), kBrentBits);
  return pair_mismatch(a, b, r <= best ? d : best_d, o);
}

}  // namespace fitlib::fit::detail
