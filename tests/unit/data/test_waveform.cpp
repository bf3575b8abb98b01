// Waveform analysis (energy method): exact sinusoids, smoothing, harmonics, seeded noise,
// force/displacement conversion and the signal-file reader.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <cmath>
#include <cstdio>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/data/waveform.hpp"
#include "fitlib/core/units.hpp"

using fitlib::core::InputError;
using fitlib::data::analyse_waveform;
using fitlib::data::WaveformOptions;
using fitlib::data::WaveformReport;

namespace {

using fitlib::core::kPi;
const std::string kWaveforms = std::string(FITLIB_TEST_DATA_DIR) + "/waveforms/";

// ε = ε_m + ε_a sin θ, σ = σ_m + ε_a (E′ sin θ + E″ cos θ) + extra(θ), θ = 2π f t + phase;
// n samples over `periods` periods (the thesis: about 5 periods in 1024 samples).
struct Sinusoid {
  double frequency_Hz = 3.0, storage_MPa = 5.0, loss_MPa = 1.2;
  double strain_amplitude = 0.02, mean_strain = 0.0, mean_stress_MPa = 0.0;
  double phase = 0.3, periods = 5.0;
  int samples = 1024;
  double third_harmonic_MPa = 0.0, third_harmonic_phase = 0.7;
  std::vector<double> t, stress, strain;
  Sinusoid& build() {
    t.clear(), stress.clear(), strain.clear();
    const double dt = periods / (frequency_Hz * samples);
    for (int i = 0; i < samples; ++i) {
      const double time = i * dt;
      const double theta = 2.0 * kPi * frequency_Hz * time + phase;
      t.push_back(time);
      strain.push_back(mean_strain + strain_amplitude * std::sin(theta));
      stress.push_back(mean_stress_MPa +
                       strain_amplitude * (storage_MPa * std::sin(theta) + loss_MPa * std::cos(theta)) +
                       third_harmonic_MPa * std::sin(3.0 * theta + third_harmonic_phase));
    }
    return *this;
  }
};

WaveformOptions no_smoothing() {
  WaveformOptions options;
  options.smoothing_window = 1;
  return options;
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(Waveform, ExactSinusoidWithoutSmoothing) {
  Sinusoid s;
  s.build();
  const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, no_smoothing());
  EXPECT_LT(rel(r.frequency_Hz, 3.0), 1e-12);
  EXPECT_NEAR(r.samples_per_period, 204.8, 1e-9);
  EXPECT_EQ(r.smoothing_window, 1);
  ASSERT_EQ(r.periods.size(), 4u);
  EXPECT_LT(rel(r.storage_MPa, 5.0), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, 1.2), 1e-9);
  EXPECT_LT(rel(r.loss_angle_deg, std::atan2(1.2, 5.0) * 180.0 / kPi), 1e-9);
  EXPECT_LT(rel(r.strain_amplitude, 0.02), 1e-12);
  EXPECT_LT(rel(r.stress_amplitude_MPa, 0.02 * std::hypot(5.0, 1.2)), 1e-12);
  EXPECT_LT(rel(r.loss_energy_MPa, kPi * 0.02 * 0.02 * 1.2), 1e-9);  // W = π ε_a² E″
  EXPECT_LT(r.storage_std_MPa, 1e-9);
  EXPECT_LT(r.max_circle_deviation, 1e-9);
  EXPECT_LT(r.max_fit_residual, 1e-9);
  EXPECT_FALSE(r.has_mean_modulus);
  EXPECT_TRUE(r.warnings.empty());
}

// A centred moving average multiplies a sinusoid of phase step x = ωΔt by
// M = sin(w x/2)/(w sin(x/2)) without shifting it; σ and ε share the factor, so σ_a/ε_a, δ and
// the loop area ratio W/(π σ_a ε_a) (both scale by M²) are unchanged.
TEST(Waveform, SmoothingAttenuatesBothSignalsAlikeAndCancels) {
  Sinusoid s;
  s.build();
  const WaveformReport automatic = analyse_waveform(s.t, s.stress, s.strain);
  EXPECT_EQ(automatic.smoothing_window, 5);  // 204.8 samples/period / 40 → 5
  EXPECT_LT(rel(automatic.storage_MPa, 5.0), 1e-9);
  EXPECT_LT(rel(automatic.loss_MPa, 1.2), 1e-9);
  for (int w : {5, 21}) {
    WaveformOptions options;
    options.smoothing_window = w;
    const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, options);
    const double x = 2.0 * kPi / 204.8;
    const double attenuation = std::sin(w * x / 2.0) / (w * std::sin(x / 2.0));
    EXPECT_LT(rel(r.smoothing_gain, attenuation), 1e-14) << w;
    EXPECT_LT(rel(r.strain_amplitude, 0.02), 1e-11) << w;  // the gain is divided out
    EXPECT_LT(rel(r.loss_energy_MPa, kPi * 0.02 * 0.02 * 1.2), 1e-9) << w;
    EXPECT_LT(rel(r.storage_MPa, 5.0), 1e-9) << w;
    EXPECT_LT(rel(r.loss_MPa, 1.2), 1e-9) << w;
  }
}

TEST(Waveform, MeanStrainGivesTheMeanModulus) {
  Sinusoid s;
  s.mean_strain = 0.02;  // the thesis' cycle from 0 to 2 ε_a
  s.mean_stress_MPa = 8.5 * 0.02;
  s.build();
  const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, no_smoothing());
  ASSERT_TRUE(r.has_mean_modulus);
  EXPECT_LT(rel(r.mean_modulus_MPa, 8.5), 1e-9);
  EXPECT_LT(rel(r.mean_strain, 0.02), 1e-12);
  EXPECT_LT(rel(r.storage_MPa, 5.0), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, 1.2), 1e-9);
  EXPECT_LT(r.max_circle_deviation, 1e-9);
}

// A third harmonic in σ adds nothing to ∮σ dε (orthogonal to ε̇) but changes σ_a. The reference
// takes σ_a from a dense brute-force scan of the closed form and W = π ε_a² E″ exactly.
TEST(Waveform, HarmonicInStressMatchesTheEnergyMethodDefinition) {
  Sinusoid s;
  s.third_harmonic_MPa = 0.01;
  s.build();
  const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, no_smoothing());
  double hi = -HUGE_VAL, lo = HUGE_VAL;
  for (int i = 0; i < 2000000; ++i) {
    const double th = 2.0 * kPi * i / 2000000.0;
    const double v = 0.02 * (5.0 * std::sin(th) + 1.2 * std::cos(th)) + 0.01 * std::sin(3.0 * th + 0.7);
    hi = std::max(hi, v), lo = std::min(lo, v);
  }
  const double stress_amplitude = 0.5 * (hi - lo);
  const double sin_delta = (kPi * 0.02 * 0.02 * 1.2) / (kPi * stress_amplitude * 0.02);
  const double storage = stress_amplitude / 0.02 * std::sqrt(1.0 - sin_delta * sin_delta);
  const double loss = stress_amplitude / 0.02 * sin_delta;
  EXPECT_LT(rel(r.stress_amplitude_MPa, stress_amplitude), 1e-10);
  EXPECT_LT(rel(r.loss_energy_MPa, kPi * 0.02 * 0.02 * 1.2), 1e-9);
  EXPECT_LT(rel(r.storage_MPa, storage), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, loss), 1e-9);
  // The strain is still a pure sinusoid, so the circle check passes.
  EXPECT_LT(r.max_circle_deviation, 1e-9);
  // Against the fundamental: E″ = W/(π ε_a²) does not see a stress harmonic at all, and E′ moves
  // only through σ_a ∈ [|E*|ε_a − s3, |E*|ε_a + s3].
  EXPECT_LT(rel(r.loss_MPa, 1.2), 1e-9);
  const double abs_modulus = std::hypot(5.0, 1.2), shift = 0.01 / 0.02;
  const double bound = std::max(
      std::abs(std::sqrt(std::pow(abs_modulus + shift, 2) - 1.44) - 5.0),
      std::abs(std::sqrt(std::pow(abs_modulus - shift, 2) - 1.44) - 5.0));
  EXPECT_LT(std::abs(r.storage_MPa - 5.0), bound);
}

TEST(Waveform, DistortedStrainFailsTheCircleCheckButKeepsTheFrequency) {
  Sinusoid s;
  s.build();
  for (std::size_t i = 0; i < s.t.size(); ++i)
    s.strain[i] += 0.002 * std::sin(2.0 * (2.0 * kPi * 3.0 * s.t[i] + 0.3));  // 10 % 2nd harmonic
  const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, no_smoothing());
  EXPECT_LT(rel(r.frequency_Hz, 3.0), 1e-12);
  EXPECT_GT(r.max_circle_deviation, 0.05);
}

// Seeded Gaussian noise on both signals: the error of each reported modulus stays within the
// standard error the report states (std over periods / √periods), with a t-like margin of 5.
TEST(Waveform, SeededNoiseErrorIsWithinTheReportedScatter) {
  Sinusoid clean;
  clean.build();
  const double noise = 0.005;  // relative to each amplitude
  double worst_storage = 0.0, worst_loss = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    fitlib::core::Rng rng(seed);
    Sinusoid s = clean;
    for (std::size_t i = 0; i < s.t.size(); ++i) {
      s.stress[i] += noise * 0.02 * std::hypot(5.0, 1.2) * rng.normal();
      s.strain[i] += noise * 0.02 * rng.normal();
    }
    const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain);
    const double se_storage = r.storage_std_MPa / 2.0, se_loss = r.loss_std_MPa / 2.0;
    EXPECT_LT(std::abs(r.storage_MPa - 5.0), 5.0 * se_storage + 1e-12) << seed;
    EXPECT_LT(std::abs(r.loss_MPa - 1.2), 5.0 * se_loss + 1e-12) << seed;
    // The noise is seen, not hidden (the 5-sample average divides its rms by about √5).
    EXPECT_GT(r.max_fit_residual, 0.25 * noise);
    worst_storage = std::max(worst_storage, rel(r.storage_MPa, 5.0));
    worst_loss = std::max(worst_loss, rel(r.loss_MPa, 1.2));
  }
  std::printf("seeded noise 0.5 %%: worst relative error E' %.2e, E'' %.2e\n", worst_storage,
              worst_loss);
  // Stated accuracy at 0.5 % noise and ≈205 samples per period (docs/data.md).
  EXPECT_LT(worst_storage, 2e-3);
  EXPECT_LT(worst_loss, 1e-2);
}

TEST(Waveform, ForceDisplacementDoubleSandwichShear) {
  fitlib::data::SpecimenInfo specimen;
  specimen.mode = fitlib::core::TestMode::shear;
  specimen.has_mode = true;
  specimen.area_mm2 = 50.8 * 12.7;
  specimen.thickness_mm = 12.7;
  specimen.n_specimens = 2;
  Sinusoid s;
  s.storage_MPa = 4.0, s.loss_MPa = 0.8, s.strain_amplitude = 0.045;
  s.build();
  std::vector<double> force, displacement, stress, strain;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    force.push_back(2.0 * specimen.area_mm2 * s.stress[i]);  // F = n A τ
    displacement.push_back(12.7 * s.strain[i]);                // u = h γ
  }
  fitlib::data::stress_strain_from_force(specimen, force, displacement, stress, strain);
  const WaveformReport r = analyse_waveform(s.t, stress, strain);
  EXPECT_LT(rel(r.storage_MPa, 4.0), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, 0.8), 1e-9);
  EXPECT_LT(rel(r.strain_amplitude, 0.045), 1e-11);
  EXPECT_LT(rel(r.stress_amplitude_MPa, 0.045 * std::hypot(4.0, 0.8)), 1e-11);  // F_a/(2A)
  specimen.thickness_mm = std::nan("");
  try {
    fitlib::data::stress_strain_from_force(specimen, force, displacement, stress, strain);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "thickness_mm");
  }
}

TEST(Waveform, ForceDisplacementCompressionWithPreload) {
  fitlib::data::SpecimenInfo specimen;
  specimen.mode = fitlib::core::TestMode::uniaxial;
  specimen.has_mode = true;
  specimen.area_mm2 = 100.0;
  specimen.length_mm = 10.0;
  Sinusoid s;
  s.frequency_Hz = 34.0, s.storage_MPa = 12.0, s.loss_MPa = 2.4, s.strain_amplitude = 0.01;
  s.mean_strain = -0.01, s.mean_stress_MPa = 10.0 * -0.01;
  s.build();
  std::vector<double> force, displacement, stress, strain;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    force.push_back(100.0 * s.stress[i]);
    displacement.push_back(10.0 * s.strain[i]);
  }
  fitlib::data::stress_strain_from_force(specimen, force, displacement, stress, strain);
  const WaveformReport r = analyse_waveform(s.t, stress, strain, no_smoothing());
  EXPECT_LT(rel(r.storage_MPa, 12.0), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, 2.4), 1e-9);
  ASSERT_TRUE(r.has_mean_modulus);
  EXPECT_LT(rel(r.mean_modulus_MPa, 10.0), 1e-9);
  EXPECT_LT(rel(r.mean_stress_MPa, -0.1), 1e-9);
}

// A "virtual testing machine" (a time integrator with adaptive steps) knows its drive
// frequency and samples irregularly: with the frequency given and no smoothing the per-period
// least-squares fits need no uniform grid.
TEST(Waveform, IrregularSamplingWithKnownFrequency) {
  Sinusoid s;
  s.build();
  fitlib::core::Rng rng(7);
  const double dt = s.t[1] - s.t[0];
  for (std::size_t i = 1; i + 1 < s.t.size(); ++i) {
    const double time = s.t[i] + 0.3 * dt * (rng.uniform() - 0.5);
    const double theta = 2.0 * kPi * 3.0 * time + 0.3;
    s.t[i] = time;
    s.strain[i] = 0.02 * std::sin(theta);
    s.stress[i] = 0.02 * (5.0 * std::sin(theta) + 1.2 * std::cos(theta));
  }
  WaveformOptions options = no_smoothing();
  options.known_frequency_Hz = 3.0;
  const WaveformReport r = analyse_waveform(s.t, s.stress, s.strain, options);
  EXPECT_EQ(r.frequency_Hz, 3.0);
  EXPECT_LT(rel(r.storage_MPa, 5.0), 1e-9);
  EXPECT_LT(rel(r.loss_MPa, 1.2), 1e-9);
  EXPECT_EQ(r.warnings.size(), 1u);  // irregular sampling is reported
}

TEST(Waveform, RefusesUnusableSignals) {
  Sinusoid s;
  s.build();
  const std::vector<double> flat(s.t.size(), 0.01);
  EXPECT_THROW(analyse_waveform(s.t, s.stress, flat), InputError);
  std::vector<double> shorter(s.stress.begin(), s.stress.end() - 1);
  EXPECT_THROW(analyse_waveform(s.t, shorter, s.strain), InputError);
  Sinusoid brief;
  brief.periods = 3.0;
  brief.build();
  EXPECT_THROW(analyse_waveform(brief.t, brief.stress, brief.strain), InputError);
  WaveformOptions two;
  two.periods = 2;
  EXPECT_EQ(analyse_waveform(brief.t, brief.stress, brief.strain, two).periods.size(), 2u);
  std::vector<double> backwards = s.t;
  std::swap(backwards[10], backwards[11]);
  EXPECT_THROW(analyse_waveform(backwards, s.stress, s.strain), InputError);
  WaveformOptions even;
  even.smoothing_window = 4;
  EXPECT_THROW(analyse_waveform(s.t, s.stress, s.strain, even), fitlib::core::UsageError);
}

TEST(WaveformFile, ShearSandwichWithHeaderMetadata) {
  const auto record = fitlib::data::read_waveform(kWaveforms + "shear_sandwich_3Hz.csv");
  EXPECT_EQ(record.specimen.mode, fitlib::core::TestMode::shear);
  EXPECT_EQ(record.specimen.n_specimens, 2);
  EXPECT_EQ(record.specimen.area_mm2, 645.16);
  EXPECT_EQ(record.time_s.size(), 1024u);
  EXPECT_EQ(record.source_sha256.size(), 64u);
  const auto report = analyse_waveform(record.time_s, record.stress_MPa, record.strain);
  const auto row = fitlib::data::waveform_row(report, record.specimen, record.source_file);
  EXPECT_EQ(row.condition.mode, fitlib::core::TestMode::shear);
  EXPECT_LT(rel(row.condition.frequency_Hz, 3.0), 1e-12);
  EXPECT_LT(rel(row.storage_MPa, 4.0), 1e-9);
  EXPECT_LT(rel(row.loss_MPa, 0.8), 1e-9);
  EXPECT_EQ(row.condition.temperature_C, 23.0);
  EXPECT_EQ(row.condition.orientation, "12");
  EXPECT_EQ(row.material, "material-1");
  EXPECT_EQ(row.specimen, "S1");
  EXPECT_FALSE(row.has_mean_modulus);
  // The row goes through the table contract unchanged (what fitcli waveform --out writes).
  fitlib::data::DynamicTestTable table;
  table.rows.push_back(row);
  const std::string path = fitlib_test::temp_path("fitlib_waveform_row.csv");
  fitlib::data::write_dynamic_table(path, table);
  const auto back = fitlib::data::read_dynamic_table(path);
  ASSERT_EQ(back.rows.size(), 1u);
  EXPECT_EQ(back.rows[0].storage_MPa, row.storage_MPa);
  EXPECT_EQ(back.rows[0].loss_MPa, row.loss_MPa);
  EXPECT_EQ(back.rows[0].condition.strain_amplitude, row.condition.strain_amplitude);
  std::remove(path.c_str());
}

TEST(WaveformFile, CompressionWithJsonSidecar) {
  const auto record = fitlib::data::read_waveform(kWaveforms + "compression_34Hz.csv",
                                                  kWaveforms + "compression_34Hz.json");
  EXPECT_EQ(record.specimen.mode, fitlib::core::TestMode::uniaxial);
  const auto report = analyse_waveform(record.time_s, record.stress_MPa, record.strain);
  EXPECT_EQ(report.smoothing_window, 1);  // 102.4 samples per period / 40 < 3
  const auto row = fitlib::data::waveform_row(report, record.specimen);
  EXPECT_LT(rel(row.storage_MPa, 12.0), 1e-9);
  EXPECT_LT(rel(row.loss_MPa, 2.4), 1e-9);
  ASSERT_TRUE(row.has_mean_modulus);
  EXPECT_LT(rel(row.mean_modulus_MPa, 10.0), 1e-9);
  EXPECT_LT(rel(row.condition.mean_strain, -0.01), 1e-9);
  EXPECT_EQ(row.condition.temperature_C, 80.0);
  EXPECT_EQ(row.condition.orientation, "22");
  // Without the sidecar the specimen constants are missing.
  try {
    fitlib::data::read_waveform(kWaveforms + "compression_34Hz.csv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "mode");
  }
}

TEST(WaveformFile, StressStrainInputWithHarmonic) {
  const auto record = fitlib::data::read_waveform(kWaveforms + "stress_strain_harmonic_60Hz.csv");
  const auto report = analyse_waveform(record.time_s, record.stress_MPa, record.strain);
  EXPECT_LT(rel(report.frequency_Hz, 60.0), 1e-12);
  EXPECT_LT(rel(report.loss_energy_MPa, kPi * 0.02 * 0.02 * 1.0), 1e-9);
  EXPECT_LT(rel(report.loss_MPa, 1.0), 1e-9);  // a stress harmonic leaves E″ = W/(π ε_a²)
}

TEST(WaveformFile, MetadataErrorsNameTheKey) {
  const std::string dir = fitlib_test::temp_dir();
  const auto write = [&](const std::string& name, const std::string& text) {
    fitlib::core::write_file_atomically(dir + name, text);
    return dir + name;
  };
  const std::string body = "time_s,stress_MPa,strain\n0,0,0\n1,1,1\n";
  const auto key_of = [](const std::string& signals, const std::string& sidecar = "") {
    try {
      fitlib::data::read_waveform(signals, sidecar);
    } catch (const InputError& e) {
      return e.key().empty() ? "line " + std::to_string(e.line()) + ":" + std::to_string(e.column())
                             : e.key();
    }
    return std::string("no error");
  };
  EXPECT_EQ(key_of(write("w1.csv", "# mode = shear\n# aera_mm2 = 5\n" + body)), "aera_mm2");
  EXPECT_EQ(key_of(write("w2.csv", "# mode = torsion\n" + body)), "mode");
  EXPECT_EQ(key_of(write("w3.csv", "# mode = shear\n# area_mm2 = abc\n" + body)), "line 2:0");
  const std::string w4 = write("w4.csv", "# mode = shear\n# temperature_C = 23\n" + body);
  EXPECT_EQ(key_of(w4, write("s4.json", R"({"temperature_C": 40})")), "temperature_C");
  EXPECT_EQ(key_of(w4, write("s5.json", R"({"temperature_C": 23.0, "n_specimens": 2})")),
            "no error");
  EXPECT_EQ(key_of(w4, write("s6.json", R"({"n_specimens": 1.5})")), "n_specimens");
  EXPECT_EQ(key_of(write("w7.csv", "# mode = shear\ntime_s,strain\n0,0\n")), "line 2:0");
  EXPECT_EQ(key_of(write("w8.csv", "# mode = shear\ntime_s,stress_MPa,strain\n0,0,0\n0,1,1\n")),
            "line 4:1");
}

TEST(WaveformFile, NegativeLossIsRefusedForTheTable) {
  Sinusoid s;
  s.loss_MPa = -0.5;  // σ lags ε: e.g. a force signal of the wrong sign convention
  s.build();
  const auto report = analyse_waveform(s.t, s.stress, s.strain);
  EXPECT_LT(report.loss_MPa, 0.0);
  EXPECT_THROW(fitlib::data::waveform_row(report, {}), InputError);
}

}  // namespace
