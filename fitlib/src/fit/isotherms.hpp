#pragma once
// Private: raw rows grouped into isotherms, each a log-log series against log10 f that continues
// beyond its ends as a local power law (docs/fitting.md, "Master curves from raw isotherms").
#include <algorithm>
#include <string>
#include <vector>

#include "fitlib/data/table.hpp"
#include "fitlib/fit/master_curve.hpp"

namespace fitlib::fit::detail {

// One modulus of an isotherm against log10 f: linear interpolation inside, a local power law
// (log-log line through the end point, slope by least squares over the end points) outside.
struct Series {
  std::vector<double> x, y;
  double slope_low = 0.0, slope_high = 0.0;

  void finish(int end_points) {
    const int n = static_cast<int>(x.size());
    const int m = std::min(std::max(end_points, 2), n);
    slope_low = slope(0, m);
    slope_high = slope(n - m, m);
  }
  double slope(int first, int count) const {
    double mx = 0, my = 0;
    for (int i = first; i < first + count; ++i) mx += x[i], my += y[i];
    mx /= count, my /= count;
    double sxx = 0, sxy = 0;
    for (int i = first; i < first + count; ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
    return sxx > 0 ? sxy / sxx : 0.0;
  }
  double value(double xq) const {
    if (xq <= x.front()) return y.front() + slope_low * (xq - x.front());
    if (xq >= x.back()) return y.back() + slope_high * (xq - x.back());
    const auto hi = std::upper_bound(x.begin(), x.end(), xq) - x.begin();
    const auto lo = hi - 1;
    const double span = x[hi] - x[lo];
    return span > 0 ? y[lo] + (y[hi] - y[lo]) * (xq - x[lo]) / span : 0.5 * (y[lo] + y[hi]);
  }
  double outside(double xq) const { return std::max({0.0, x.front() - xq, xq - x.back()}); }
};

struct Isotherm {
  std::vector<std::string> sets;
  double temperature_C = 0.0;
  std::vector<int> rows;
  Series storage, loss;  // log10 moduli (times the entropic factor when chosen)
  bool has_loss = true;
};

// "a+b" for the sets of an isotherm.
std::string set_label(const Isotherm& iso);

// Rows → isotherms sorted by temperature; duplicates (by same_temperature_C) merged.
std::vector<Isotherm> group_isotherms(const data::DynamicTestTable& raw, const MasterCurveOptions& o,
                                      std::vector<std::string>& messages);

// The isotherm's storage and loss series (log10 moduli, times the entropic factor when chosen).
void fill_series(Isotherm& iso, const data::DynamicTestTable& raw, const MasterCurveOptions& o, double reference_C);

// Index of the temperature nearest reference_C (the first of equals): the anchor of the shifts.
int nearest_temperature(const std::vector<double>& temperatures_C, double reference_C);

}  // namespace fitlib::fit::detail
