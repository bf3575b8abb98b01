#pragma once
// The benchmarks' timing: the median wall time of repeated calls (robust to a loaded machine's
// outliers).
#include <algorithm>
#include <vector>

#include "fitlib/core/timer.hpp"

// Median wall time (s) of `repeats` calls of f.
template <class F>
double median_time(int repeats, F&& f) {
  std::vector<double> t;
  for (int k = 0; k < repeats; ++k) {
    const fitlib::core::Stopwatch w;
    f();
    t.push_back(w.seconds());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}
