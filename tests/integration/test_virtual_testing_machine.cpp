// The time integrator as a virtual testing machine: its stress signal, analysed like a lab
// record (energy method, four periods), returns the complex form's moduli (issue 3, item 7).
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/waveform.hpp"

using namespace fitlib;

namespace {

data::WaveformReport run_machine(const card::Card& card, const model::TestCondition& c, int cycles,
                                 int steps_per_cycle) {
  const auto m = card.model();
  const auto p = card.values();
  model::StrainHistory h;
  const double period = 1.0 / c.frequency_Hz;
  for (int k = 0; k <= cycles * steps_per_cycle; ++k) {
    const double t = period * k / steps_per_cycle;
    h.time_s.push_back(t);
    // Thesis procedure: mean strain = one amplitude (cycle from 0 to 2ε_a).
    h.strain.push_back(c.mean_strain + c.strain_amplitude * std::sin(core::angular_frequency(c.frequency_Hz) * t));
  }
  const auto stress = m->stress_response(p.data(), c, h);
  data::WaveformOptions o;
  o.known_frequency_Hz = c.frequency_Hz;
  return data::analyse_waveform(h.time_s, stress, h.strain, o);
}

}  // namespace

TEST(VirtualTestingMachine, PronyCardSignalsGiveTheComplexModuli) {
  const auto card = card::load_card(source_path("datasets/cards/synthetic-prony-shear-true.json"));
  model::TestCondition c;
  c.frequency_Hz = 3.0;
  c.strain_amplitude = 0.01;
  c.mean_strain = 0.01;
  // 600 cycles = 20 × the longest relaxation time: the mean stress has stopped drifting.
  const auto report = run_machine(card, c, 600, 200);
  const auto expected = card.model()->moduli(card.values().data(), c);
  EXPECT_NEAR(report.storage_MPa, expected.storage, 1e-4 * expected.storage);
  EXPECT_NEAR(report.loss_MPa, expected.loss, 1e-4 * expected.storage);
}

TEST(VirtualTestingMachine, FritzsonCardWithDamageAndTemperatureGivesTheComplexModuli) {
  const auto card = card::load_card(source_path("datasets/cards/material-2-true.json"));
  model::TestCondition c;
  c.mode = model::TestMode::shear;
  c.orientation = "12";
  c.frequency_Hz = 34.0;
  c.temperature_C = 60.0;
  c.strain_amplitude = 0.015;
  c.mean_strain = 0.015;
  const auto report = run_machine(card, c, 200, 256);
  const auto expected = card.model()->moduli(card.values().data(), c);
  // Damage settles over the first cycles; after 200 the loop is steady (0.5 %, docs/fritzson.md).
  EXPECT_NEAR(report.storage_MPa, expected.storage, 5e-3 * expected.storage);
  EXPECT_NEAR(report.loss_MPa, expected.loss, 5e-3 * expected.storage);
  EXPECT_LT(report.storage_std_MPa, 1e-3 * expected.storage);  // the four periods agree
}
