#pragma once
// What a dynamic test imposes: mode, orientation, frequency, temperature, amplitude, mean strain.
// The vocabulary that test tables (data) and models (model) share, so it lives below both.
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace fitlib::core {

enum class TestMode { shear, uniaxial, bulk };

// "shear" | "uniaxial" (aliases "tension", "compression") | "bulk"; nullopt otherwise.
inline std::optional<TestMode> test_mode_from_label(const std::string& text) {
  if (text == "shear") return TestMode::shear;
  if (text == "uniaxial" || text == "tension" || text == "compression") return TestMode::uniaxial;
  if (text == "bulk") return TestMode::bulk;
  return std::nullopt;
}

inline const char* to_string(TestMode mode) {
  switch (mode) {
    case TestMode::shear: return "shear";
    case TestMode::uniaxial: return "uniaxial";
    case TestMode::bulk: return "bulk";
  }
  return "?";
}

struct TestCondition {
  TestMode mode = TestMode::shear;
  // Thesis label ("11", "22", "33", "12", "13", "23", ...); empty = isotropic / not given.
  std::string orientation;
  double frequency_Hz = 1.0;
  // NaN = the card's reference temperature.
  double temperature_C = std::numeric_limits<double>::quiet_NaN();
  // Amplitude of the oscillating strain (shear: engineering γ_a); 0 = small-amplitude limit.
  double strain_amplitude = 0.0;
  double mean_strain = 0.0;

  bool has_temperature() const { return !std::isnan(temperature_C); }
};

}  // namespace fitlib::core
