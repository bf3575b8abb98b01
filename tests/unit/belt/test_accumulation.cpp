// Zupancic–Emri strain accumulation: the O(K) closed form against the term-by-term sum of Eq. (5)
// and against time integration of the hereditary integral; the paper's qualitative findings.
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/belt/accumulation.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using fitlib::core::kPi;

TEST(Accumulation, ClosedFormMatchesDirectSumAndTimeIntegration) {
  for (const auto& name : spectrum_shape_names()) {
    const auto s = spectrum_shape(name, 1e-2, 4, 1e-3);
    for (long N : {1L, 7L, 300L}) {
      for (double omega : {1.0, 100.0, 1e4}) {
        const double closed = accumulated_strain(s, 2.0, N, omega, kPi);
        const double direct = accumulated_strain_direct_sum(s, 2.0, N, omega, kPi);
        const double integrated = accumulated_strain_time_integration(s, 2.0, N, omega, kPi);
        ASSERT_GT(closed, 0.0);
        EXPECT_NEAR(closed / direct, 1.0, 1e-8) << name << " N=" << N << " w=" << omega;
        EXPECT_NEAR(closed / integrated, 1.0, 1e-8) << name << " N=" << N << " w=" << omega;
      }
    }
  }
}

TEST(Accumulation, SingleLineAnalytic) {
  // One Kelvin line after one cycle: L τ0 (1 − e^{−π/(ωλ)}) e^{−κ/(ωλ)}.
  RetardationSpectrum s{0.0, {0.5}, {0.02}};
  const double w = 50, k = 2.0, a = 1 / (w * 0.02);
  EXPECT_NEAR(accumulated_strain(s, 3.0, 1, w, k), 3.0 * 0.5 * (1 - std::exp(-kPi * a)) * std::exp(-k * a), 1e-15);
  // N → ∞: geometric series limit.
  const double q = std::exp(-2 * a * (k + kPi));
  EXPECT_NEAR(accumulated_strain(s, 3.0, 1e9, w, k),
              3.0 * 0.5 * (1 - std::exp(-kPi * a)) * std::exp(-k * a) / (1 - q), 1e-12);
}

TEST(Accumulation, PaperFindingsAtKappaPi) {
  const long N = 10000;
  auto gamma = [&](const std::string& shape, double w) {
    return accumulated_strain(spectrum_shape(shape), 1.0, N, w, kPi);
  };
  // Wedge accumulates least at ω = 100 1/s.
  for (const auto& name : {"box", "gauss", "lorentzian", "ramp"}) EXPECT_LT(gamma("wedge", 100), gamma(name, 100)) << name;
  // Box: nearly independent of ω over the decades it covers.
  const double b1 = gamma("box", 100), b2 = gamma("box", 1000), b3 = gamma("box", 1e4);
  EXPECT_NEAR(b1 / b2, 1.0, 0.1);
  EXPECT_NEAR(b3 / b2, 1.0, 0.1);
  // Ramp: more at low ω.
  EXPECT_GT(gamma("ramp", 1), gamma("ramp", 100));
  EXPECT_GT(gamma("ramp", 100), gamma("ramp", 1e4));
  // Accumulation grows with N and most strongly at the start.
  const auto g = spectrum_shape("gauss");
  const double g10 = accumulated_strain(g, 1, 10, 100, kPi), g20 = accumulated_strain(g, 1, 20, 100, kPi);
  const double g1000 = accumulated_strain(g, 1, 1000, 100, kPi), g1010 = accumulated_strain(g, 1, 1010, 100, kPi);
  EXPECT_GT(g20 - g10, g1010 - g1000);
}

TEST(Accumulation, CriticalCyclesBracketTheLimit) {
  const auto s = spectrum_shape("gauss");
  const double limit = 0.5 * accumulated_strain(s, 1.0, 10000, 100, kPi);
  const long Nc = critical_cycles(s, 1.0, 100, kPi, limit, 10000);
  ASSERT_GT(Nc, 0);
  EXPECT_GE(accumulated_strain(s, 1.0, Nc, 100, kPi), limit);
  EXPECT_LT(accumulated_strain(s, 1.0, Nc - 1, 100, kPi), limit);
  EXPECT_EQ(critical_cycles(s, 1.0, 100, kPi, 10 * limit, 10000), -1);
}

TEST(Accumulation, BadInputNamesKey) {
  EXPECT_THROW(spectrum_shape("triangle"), fitlib::core::InputError);
  RetardationSpectrum bad{0.0, {1.0}, {-1.0}};
  EXPECT_THROW(validate(bad), fitlib::core::InputError);
  EXPECT_THROW(accumulated_strain(spectrum_shape("box"), 1, 10, 0.0, kPi), fitlib::core::InputError);
}
