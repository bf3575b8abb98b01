#pragma once
// Waveform analysis (Report V §4.8; spec material-tests-and-surfaces.md §2.1, formats.md §2):
// from sampled stress and strain of a steady sinusoidal test to E′, E″ by the energy method.
//
// Method, per analysed period (the last `periods` whole periods of the record):
//  1. frequency: zero crossings of the de-meaned strain give a first estimate; a Gauss–Newton
//     least-squares fit of a K-harmonic Fourier series to the whole strain record refines it;
//  2. centred moving average of both signals (same window, so their ratio and phase are kept);
//  3. each signal on each period is represented by its least-squares trigonometric polynomial
//     of degree K (c + Σ a_k cos kθ + b_k sin kθ); this gives ε̇ in closed form;
//  4. W_loss = ∮σ dε = ∫σ ε̇ dt = π Σ k (a_k^σ b_k^ε − b_k^σ a_k^ε) (exact for that polynomial);
//  5. amplitudes and means from the extreme points of the polynomial (found by Newton steps);
//     amplitudes divided by the moving average's gain M at the fundamental, W by M²;
//  6. sin δ = W_loss/(π σ_a ε_a); E′ = (σ_a/ε_a) cos δ, E″ = (σ_a/ε_a) sin δ, E_m = σ_m/ε_m;
//  7. circle check: max over samples of |√((ε−ε_m)² + (ε̇/ω)²) − ε_a| / ε_a.
// Exact sinusoids give E′, E″ to round-off with or without smoothing (see docs/data.md).
#include <string>
#include <vector>

#include "fitlib/data/specimen.hpp"
#include "fitlib/data/table.hpp"

namespace fitlib::data {

struct WaveformOptions {
  int periods = 4;  // successive whole periods analysed (the last ones of the record)
  // Centred moving-average width in samples (odd): 0 = automatic, the largest odd number not
  // above samples_per_period × smoothing_period_fraction (5 at the thesis' ≈205 samples per
  // period); 1 = no smoothing.
  int smoothing_window = 0;
  double smoothing_period_fraction = 1.0 / 40.0;
  // Degree K of the per-period trigonometric fit (capped at (samples per period − 1)/4).
  int harmonics = 10;
  // Known drive frequency; 0 = from the signal.
  double known_frequency_Hz = 0.0;
  // The mean modulus is reported only when |ε_m| ≥ this × ε_a (a deliberate mean strain).
  double mean_strain_threshold = 0.01;
};

struct PeriodResult {
  double start_s = 0.0;
  double stress_amplitude_MPa = 0.0, strain_amplitude = 0.0;
  double mean_stress_MPa = 0.0, mean_strain = 0.0;
  double loss_energy_MPa = 0.0;  // W_loss per cycle, MPa = mJ/mm³
  double loss_angle_rad = 0.0;
  double storage_MPa = 0.0, loss_MPa = 0.0;
  double circle_deviation = 0.0;  // max relative radial deviation of (ε − ε_m, ε̇/ω)
  double fit_residual = 0.0;      // rms (samples − fit) / amplitude, larger of σ and ε
  int samples = 0;
};

struct WaveformReport {
  double frequency_Hz = 0.0;
  double samples_per_period = 0.0;
  int smoothing_window = 1;
  double smoothing_gain = 1.0;  // M = sin(wωΔt/2)/(w sin(ωΔt/2)), already divided out
  int harmonics = 0;
  std::vector<PeriodResult> periods;
  // Means over the periods (what the thesis reports) and their sample standard deviations.
  double storage_MPa = 0.0, loss_MPa = 0.0, loss_angle_deg = 0.0, tan_delta = 0.0;
  double storage_std_MPa = 0.0, loss_std_MPa = 0.0, loss_angle_std_deg = 0.0;
  double stress_amplitude_MPa = 0.0, strain_amplitude = 0.0;
  double mean_stress_MPa = 0.0, mean_strain = 0.0;
  double loss_energy_MPa = 0.0;
  double mean_modulus_MPa = 0.0;
  bool has_mean_modulus = false;
  double max_circle_deviation = 0.0;
  double max_fit_residual = 0.0;
  std::vector<std::string> warnings;  // e.g. irregular sampling
};

// The analysis on plain vectors (for measured records and for a simulated "virtual testing
// machine"). time_s strictly increasing (uniform steps for the smoothing), equal lengths.
// Throws InputError for unusable signals (too short, no oscillation, fewer than `periods`
// whole periods, loop area beyond π σ_a ε_a).
WaveformReport analyse_waveform(const std::vector<double>& time_s,
                                const std::vector<double>& stress_MPa,
                                const std::vector<double>& strain,
                                const WaveformOptions& options = {});

struct WaveformRecord {
  std::vector<double> time_s, stress_MPa, strain;
  SpecimenInfo specimen;
  std::string source_file, source_sha256;
};

// Reads a signal CSV: columns time_s and (force_N, displacement_mm) or (stress_MPa, strain);
// metadata in `# key = value` lines and/or a JSON sidecar object (keys: mode, area_mm2,
// thickness_mm, length_mm, volume_mm3, n_specimens, temperature_C, material, specimen,
// orientation). A key given in both with different values, an unknown key or a bad value is an
// InputError naming the file and key (or line and column).
WaveformRecord read_waveform(const std::string& signals_path, const std::string& sidecar_path = "");

// analyse_waveform on a record read from a file; its errors name that file.
WaveformReport analyse_record(const WaveformRecord& record, const WaveformOptions& options = {});

// The dynamic-test row of an analysis (frequency, temperature, amplitudes, E′, E″, E_m).
// Throws InputError if E″ < 0 (stress lagging strain: check the signs of the signals).
DynamicTestRow waveform_row(const WaveformReport& report, const SpecimenInfo& specimen,
                            const std::string& source_file = "");

}  // namespace fitlib::data
