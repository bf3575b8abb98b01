#include <gtest/gtest.h>
#include <cstdio>
#include "fit_testing.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/core/timer.hpp"
using namespace fitlib;
using namespace fitlib::fit::testing;
TEST(Scratch, Explore) {
  for (int n : {15, 30}) {
  auto m = prony(n);
  std::vector<double> p{1.0};
  for (int i = 0; i < n; ++i) p.push_back(0.5 + std::fmod(0.37 * i, 1.0));
  for (double tau : log_frequencies(2e-8, 1e5, n)) p.push_back(tau);
  auto table = synthetic_table(*m, p, log_frequencies(1e-6, 1e8, 200), 0.01, 2);
  for (auto b : {fit::Backend::nnls, fit::Backend::automatic}) {
    fit::FitOptions o; o.backend = b; o.polish = false;
    auto r = fit::fit(m, table, o);
    std::printf("n=%d %s: rms %.4f %.4f cost %.4f conv %d it %d t %.1f ms\n", n, r.backend_used.c_str(), r.metrics.rms_log10_storage, r.metrics.rms_log10_loss, r.metrics.cost, r.metrics.converged, r.metrics.iterations, 1e3*r.metrics.wall_time_s);
    for (auto& msg : r.messages) std::printf("   %s\n", msg.substr(0,200).c_str());
  }
  // jacobian cost
  Eigen::MatrixXd J(3, m->size());
  core::Stopwatch w;
  for (int k = 0; k < 10; ++k) for (auto& row : table.rows) m->moduli(p.data(), row.condition, J);
  std::printf("jacobian pass over 200 rows: %.3f ms\n", w.seconds() * 100);
  w.restart();
  for (int k = 0; k < 10; ++k) for (auto& row : table.rows) m->moduli(p.data(), row.condition);
  std::printf("value pass over 200 rows: %.3f ms\n", w.seconds() * 100);
  }
}
