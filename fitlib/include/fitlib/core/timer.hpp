#pragma once
#include <chrono>

namespace fitlib::core {

// Wall-clock stopwatch in seconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Mean wall time of f() in seconds: calls it 1, 2, 4, … times until one batch lasts min_total_s
// (benchmarks).
template <typename F>
double seconds_per_call(F f, double min_total_s = 0.2) {
  for (int n = 1;; n *= 2) {
    Stopwatch watch;
    for (int k = 0; k < n; ++k) f();
    const double dt = watch.seconds();
    if (dt >= min_total_s) return dt / n;
  }
}

}  // namespace fitlib::core
