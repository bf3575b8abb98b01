#pragma once
// Synthetic Prony data of known truth for the card tests: a smooth spectrum one term per decade,
// and the card's error against the noise-free curve between the data's frequencies.
#include <cmath>
#include <cstdint>
#include <vector>

#include "../fit/fit_testing.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fit/fit.hpp"

namespace fitlib::card::testing {

// A smooth truth: `terms` Prony terms one per decade from τ_lo, moduli on a log-normal bump
// whose centre and width the seed moves, E_inf 1 MPa.
struct Truth {
  model::ModelPtr model;
  std::vector<double> p;
};
inline Truth smooth_truth(int terms, double tau_lo_s, std::uint64_t seed) {
  core::Rng rng(seed);
  Truth t{fit::testing::prony(terms), {}};
  const double centre = 0.3 + 0.4 * rng.uniform(), width = 0.2 + 0.15 * rng.uniform();
  t.p.push_back(1.0);
  for (int i = 0; i < terms; ++i) {
    const double x = (i + 0.5) / terms - centre;
    t.p.push_back(40.0 * std::exp(-0.5 * x * x / (width * width)) + 0.5);
  }
  for (int i = 0; i < terms; ++i) t.p.push_back(tau_lo_s * std::pow(10.0, i));
  return t;
}

struct HeldOut {
  double storage = 0.0, loss = 0.0;
};

// rms log10 of the card against the noise-free truth midway between the data's frequencies.
inline HeldOut held_out(const fit::FitResult& r, const Truth& t, const std::vector<double>& frequencies) {
  HeldOut h;
  int n = 0;
  for (std::size_t k = 0; k + 1 < frequencies.size(); ++k, ++n) {
    model::TestCondition c;
    c.mode = model::TestMode::shear;
    c.frequency_Hz = std::sqrt(frequencies[k] * frequencies[k + 1]);
    const auto a = r.model->moduli(r.values.data(), c);
    const auto b = t.model->moduli(t.p.data(), c);
    h.storage += std::pow(std::log10(a.storage / b.storage), 2);
    h.loss += std::pow(std::log10(a.loss / b.loss), 2);
  }
  h.storage = std::sqrt(h.storage / n);
  h.loss = std::sqrt(h.loss / n);
  return h;
}

}  // namespace fitlib::card::testing
