#include <gtest/gtest.h>
#include <cstdio>
#include "fit_testing.hpp"
#include "fitlib/fit/fit.hpp"
using namespace fitlib;
using namespace fitlib::fit::testing;
TEST(Scratch, Explore) {
  const auto model = prony(5);
  const auto truth = prony_parameters(0.2, {1.0, 3.0, 2.0, 0.5, 4.0}, {1e-10, 1e-5, 1.0, 1e5, 1e10});
  const auto table = synthetic_table(*model, truth, log_frequencies(1e-12, 1e12, 100), 0.01, 11);
  for (bool g : {false, true}) for (auto b : {fit::Backend::automatic, fit::Backend::staged}) {
    fit::FitOptions o; o.global = g; o.backend = b;
    auto r = fit::fit(model, table, o);
    std::printf("%s g=%d: rms %.4f %.4f cost %.4f conv %d t %.1f ms\n", r.backend_used.c_str(), g, r.metrics.rms_log10_storage, r.metrics.rms_log10_loss, r.metrics.cost, r.metrics.converged, 1e3*r.metrics.wall_time_s);
    for (double v : r.values) std::printf(" %.3g", v); std::printf("\n");
  }
}
