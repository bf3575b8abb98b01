#include "materials.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fitlib/core/rng.hpp"
#include "fitlib/model/fritzson.hpp"

namespace fritzson_test {

using fitlib::model::TestMode;

std::vector<double> material1_parameters() {
  return {4000.0,                                                   // K
          // G_Im G_Id G_Iv  tau_I  k_I  beta1 alpha1 mu   beta2 alpha2 c1     c2
          2.5, 2.0, 0.21, 0.008, 2.5, 0.25, 0.6, -2.0, 0.5, 0.5, 0.0065, 0.008,
          0.6,                                                      // C_d
          // C33_Am C33_Ad C33_Av tau_A1 k_A1 beta1 alpha1 mu beta2 alpha2 c1 c2
          10.0, 8.0, 0.7, 0.008, 2.5, 0.4, 0.5, -2.2, 0.5, 0.5, 0.006, 0.008,
          // C44_Am C44_Ad C44_Av tau_A2 k_A2 beta1 alpha1 mu beta2 alpha2 c1 c2
          1.2, 1.0, 0.1, 0.008, 2.5, 0.35, 0.6, -2.0, 0.5, 0.5, 0.006, 0.008};
}

std::vector<double> material2_parameters() {
  return {2000.0, 1.0, 0.9, 0.085, 0.006, 2.5, 0.15, 0.6, -2.0, 0.5, 0.5, 0.005, 0.007, 0.6};
}

namespace {

struct Series {
  TestMode mode;
  const char* orientation;
  std::vector<double> amplitudes, temperatures_C, frequencies_Hz;
  int specimens;
  bool drop_largest_amplitude_at_highest_temperature;  // shear (Report V L4248)
};

}  // namespace

fitlib::data::DynamicTestTable material_table(int material) {
  const bool m1 = material == 1;
  const std::vector<double> p = m1 ? material1_parameters() : material2_parameters();
  const auto model = fitlib::model::fritzson::make_fritzson_model(
      m1 ? "fritzson" : "fritzson-iso", {{"reference_C", kReferenceC}});
  const std::vector<double> f = {3.0, 34.0, 60.0}, t3 = {23.0, 60.0, 100.0}, t2 = {23.0, 100.0};
  std::vector<Series> design;
  if (m1) {  // Report V Figs 6.1–6.8: N = 36, 24, 47, 42
    design = {{TestMode::uniaxial, "22", {0.005, 0.015}, t2, f, 3, false},
              {TestMode::uniaxial, "33", {0.005, 0.01}, t2, f, 2, false},
              {TestMode::shear, "12", {0.005, 0.015, 0.045}, t3, f, 2, true},
              {TestMode::shear, "23", {0.005, 0.015, 0.045}, t3, f, 2, true},
              {TestMode::bulk, "", {0.001}, {23.0}, {0.01, 1.0}, 2, false}};
  } else {  // Figs 6.9–6.16: N = 24, 24, 42, 42
    design = {{TestMode::uniaxial, "22", {0.005, 0.015}, t2, f, 2, false},
              {TestMode::uniaxial, "33", {0.005, 0.015}, t2, f, 2, false},
              {TestMode::shear, "13", {0.005, 0.015, 0.045}, t3, f, 2, true},
              {TestMode::shear, "23", {0.005, 0.015, 0.045}, t3, f, 2, true},
              {TestMode::bulk, "", {0.001}, {23.0}, {0.01, 1.0}, 2, false}};
  }
  fitlib::core::Rng rng(m1 ? 1001 : 1002);
  constexpr double kScatter = 0.015;  // specimen-to-specimen 1–2 % (Report V §6)
  fitlib::data::DynamicTestTable table;
  int specimen_id = 0;
  for (const Series& s : design) {
    for (double T : s.temperatures_C) {
      for (size_t ia = 0; ia < s.amplitudes.size(); ++ia) {
        if (s.drop_largest_amplitude_at_highest_temperature && T == s.temperatures_C.back() &&
            ia + 1 == s.amplitudes.size())
          continue;
        for (double freq : s.frequencies_Hz) {
          fitlib::model::TestCondition c;
          c.mode = s.mode;
          c.orientation = s.orientation;
          c.frequency_Hz = freq;
          c.temperature_C = T;
          c.strain_amplitude = s.amplitudes[ia];
          // Mean strain one amplitude (Report V §4.9): compression for uniaxial and bulk.
          c.mean_strain = s.mode == TestMode::shear ? s.amplitudes[ia] : -s.amplitudes[ia];
          const auto m = model->moduli(p.data(), c);
          for (int k = 0; k < s.specimens; ++k) {
            fitlib::data::DynamicTestRow row;
            row.condition = c;
            // Rounded to 4 significant figures: a lab's 3–4 significant figures (Report V L3790).
            auto noisy = [&](double v) {
              char text[32];
              std::snprintf(text, sizeof text, "%.4g", v * (1.0 + kScatter * rng.normal()));
              return std::strtod(text, nullptr);
            };
            row.storage_MPa = noisy(m.storage);
            row.loss_MPa = noisy(m.loss);
            row.mean_modulus_MPa = noisy(m.mean);
            row.has_mean_modulus = true;
            row.material = m1 ? "material-1" : "material-2";
            row.specimen = "S" + std::to_string(++specimen_id);
            table.rows.push_back(row);
          }
        }
      }
    }
  }
  return table;
}

}  // namespace fritzson_test
