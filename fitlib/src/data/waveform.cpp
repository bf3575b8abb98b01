// Waveform analysis by the energy method (Report V §4.8); see waveform.hpp for the method.
#include "fitlib/data/waveform.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "trig_series.hpp"

namespace fitlib::data {
namespace {

using core::InputError;
using trig::TrigSeries;
constexpr double kTwoPi = 2.0 * core::kPi;

// Upward crossings of `signal` through its mid-range, with hysteresis of a quarter of the
// half-range so that noise does not add crossings; times by linear interpolation.
std::vector<double> upward_crossings(const std::vector<double>& time_s,
                                     const std::vector<double>& signal) {
  const auto [lo, hi] = std::minmax_element(signal.begin(), signal.end());
  const double mid = 0.5 * (*lo + *hi), band = 0.25 * 0.5 * (*hi - *lo);
  std::vector<double> crossings;
  bool armed = false;
  for (std::size_t i = 1; i < signal.size(); ++i) {
    if (signal[i] < mid - band) armed = true;
    if (armed && signal[i] >= mid + band) {
      std::size_t j = i;
      while (j > 0 && signal[j - 1] >= mid) --j;
      if (j > 0) {
        const double fraction = (mid - signal[j - 1]) / (signal[j] - signal[j - 1]);
        crossings.push_back(time_s[j - 1] + fraction * (time_s[j] - time_s[j - 1]));
      }
      armed = false;
    }
  }
  return crossings;
}

// Centred moving average over `window` samples; the (window−1)/2 samples at each end, where the
// window would be cut, are dropped (from time too), so no end effects remain.
std::vector<double> moving_average(const std::vector<double>& x, int window) {
  const int half = window / 2;
  std::vector<double> smooth;
  if (static_cast<int>(x.size()) <= 2 * half) return smooth;
  double sum = std::accumulate(x.begin(), x.begin() + window, 0.0);
  smooth.push_back(sum / window);
  for (std::size_t i = window; i < x.size(); ++i) {
    sum += x[i] - x[i - window];
    smooth.push_back(sum / window);
  }
  return smooth;
}

double mean_of(const std::vector<PeriodResult>& periods, double PeriodResult::*field) {
  double sum = 0.0;
  for (const auto& p : periods) sum += p.*field;
  return sum / static_cast<double>(periods.size());
}

double std_of(const std::vector<PeriodResult>& periods, double PeriodResult::*field) {
  if (periods.size() < 2) return 0.0;
  const double mean = mean_of(periods, field);
  double sum = 0.0;
  for (const auto& p : periods) sum += (p.*field - mean) * (p.*field - mean);
  return std::sqrt(sum / static_cast<double>(periods.size() - 1));
}

void check_signals(const std::vector<double>& time_s, const std::vector<double>& stress_MPa,
                   const std::vector<double>& strain) {
  if (stress_MPa.size() != time_s.size() || strain.size() != time_s.size())
    throw InputError("time, stress and strain signals differ in length");
  if (time_s.size() < 16) throw InputError("signal has fewer than 16 samples");
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    if (!std::isfinite(time_s[i]) || !std::isfinite(stress_MPa[i]) || !std::isfinite(strain[i]))
      throw InputError("sample " + std::to_string(i) + " is not finite");
    if (i > 0 && !(time_s[i] > time_s[i - 1]))
      throw InputError("time is not strictly increasing at sample " + std::to_string(i));
  }
}

// Every reported figure must be finite before anything is written (overflowing signals).
void check_report_finite(const WaveformReport& r) {
  const std::pair<const char*, double> figures[] = {
      {"frequency", r.frequency_Hz},         {"storage modulus", r.storage_MPa},
      {"loss modulus", r.loss_MPa},          {"tan delta", r.tan_delta},
      {"stress amplitude", r.stress_amplitude_MPa}, {"strain amplitude", r.strain_amplitude},
      {"mean stress", r.mean_stress_MPa},    {"mean strain", r.mean_strain},
      {"loss energy", r.loss_energy_MPa},    {"storage std", r.storage_std_MPa},
      {"loss std", r.loss_std_MPa},          {"mean modulus", r.mean_modulus_MPa}};
  for (const auto& [what, value] : figures)
    if (!std::isfinite(value)) throw core::NumericalError("waveform analysis: " + std::string(what) + " is not finite");
}

void check_options(const WaveformOptions& options) {
  if (options.periods < 1) throw core::UsageError("waveform: periods must be at least 1");
  if (options.harmonics < 1) throw core::UsageError("waveform: harmonics must be at least 1");
  if (options.smoothing_window < 0 || (options.smoothing_window > 0 && options.smoothing_window % 2 == 0))
    throw core::UsageError("waveform: smoothing window must be an odd number of samples (1 = off)");
}

// The mean time step; a warning when steps vary by more than 0.1 % of it.
double mean_time_step(const std::vector<double>& time_s, std::vector<std::string>& warnings) {
  const std::size_t n = time_s.size();
  const double dt = (time_s.back() - time_s.front()) / static_cast<double>(n - 1);
  double max_step_deviation = 0.0;
  for (std::size_t i = 1; i < n; ++i)
    max_step_deviation = std::max(max_step_deviation, std::abs(time_s[i] - time_s[i - 1] - dt));
  if (max_step_deviation > 1e-3 * dt)
    warnings.push_back("irregular sampling (time step varies by up to " +
                       core::format_number(100.0 * max_step_deviation / dt, 3) +
                       " %); the moving average assumes uniform steps");
  return dt;
}

// Step 1: zero crossings, then a least-squares refinement on the whole strain record. Sets the
// report's frequency, samples per period and harmonics (the degree K).
void find_frequency(const std::vector<double>& time_s, const std::vector<double>& strain,
                    const WaveformOptions& options, double dt, WaveformReport& report) {
  const std::size_t n = time_s.size();
  const auto [strain_lo, strain_hi] = std::minmax_element(strain.begin(), strain.end());
  if (!(*strain_hi > *strain_lo)) throw InputError("strain signal does not oscillate");
  double frequency_Hz = options.known_frequency_Hz;
  if (!(frequency_Hz > 0.0)) {
    const std::vector<double> crossings = upward_crossings(time_s, strain);
    if (crossings.size() < 2)
      throw InputError("strain signal holds fewer than two cycles; frequency unknown");
    frequency_Hz = static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
  }
  double samples_per_period = 1.0 / (frequency_Hz * dt);
  // Checked in double before any conversion to int (a tiny known frequency would overflow it).
  if (!(samples_per_period * options.periods <= static_cast<double>(n)))
    throw InputError("the record holds fewer than " + std::to_string(options.periods) +
                     " periods at " + core::short_number(frequency_Hz) + " Hz");
  if (samples_per_period < 5.0)
    throw InputError("fewer than 5 samples per period (" + std::to_string(samples_per_period) + ")");
  const int degree = std::max(1, std::min(options.harmonics,
                                          static_cast<int>((samples_per_period - 1.0) / 4.0)));
  if (!(options.known_frequency_Hz > 0.0))
    frequency_Hz = trig::refine_angular_frequency(time_s, strain, kTwoPi * frequency_Hz, degree,
                                                  report.warnings) / kTwoPi;
  report.frequency_Hz = frequency_Hz;
  report.samples_per_period = 1.0 / (frequency_Hz * dt);
  report.harmonics = degree;
}

// Step 2: the moving-average width, and its gain M at the fundamental; amplitudes and W are
// divided by M (W by M²) so that a sinusoid is reported at its true size. Ratios (E′, E″, δ)
// need no correction.
void choose_smoothing(const WaveformOptions& options, double dt, WaveformReport& report) {
  int window = options.smoothing_window;
  if (window == 0) {
    window = static_cast<int>(report.samples_per_period * options.smoothing_period_fraction);
    if (window % 2 == 0) --window;
    window = std::max(1, window);
  }
  report.smoothing_window = window;
  const double omega = kTwoPi * report.frequency_Hz;
  const double half_step = 0.5 * omega * dt;
  report.smoothing_gain = window == 1 ? 1.0 : std::sin(window * half_step) / (window * std::sin(half_step));
}

// The smoothed signals (time too, to keep the samples aligned).
struct SmoothSignals {
  std::vector<double> t, sigma, eps;
};

// Amplitudes, means and the modulus plausibility check of one period's two polynomials.
void period_amplitudes(const TrigSeries& s, const TrigSeries& e, double gain, PeriodResult& r,
                       double& smooth_stress_amplitude, double& smooth_strain_amplitude) {
  const auto [sigma_max, sigma_min] = trig::extremes(s);
  const auto [eps_max, eps_min] = trig::extremes(e);
  smooth_stress_amplitude = 0.5 * (sigma_max - sigma_min);
  smooth_strain_amplitude = 0.5 * (eps_max - eps_min);
  if (!(smooth_strain_amplitude > 0.0)) throw InputError("strain amplitude is zero in a period");
  if (!(smooth_stress_amplitude > 0.0)) throw InputError("stress amplitude is zero in a period");
  // 1e12 MPa is far above any solid (steel: 2e5 MPa): beyond it the strain signal is noise.
  if (!(smooth_stress_amplitude / smooth_strain_amplitude <= 1e12))
    throw InputError("stress amplitude / strain amplitude is not a plausible modulus (strain amplitude " +
                     core::short_number(smooth_strain_amplitude) + ")");
  // A constant stress (the amplitude is round-off) gave a row with a modulus of 2e-15 MPa: below
  // 1 Pa (1e-6 MPa) no solid answers, and an amplitude below 1e-9 of the stress level is noise.
  if (!(smooth_stress_amplitude / smooth_strain_amplitude >= 1e-6) ||
      smooth_stress_amplitude <= 1e-9 * std::max(std::abs(sigma_max), std::abs(sigma_min)))
    throw InputError("the stress signal does not oscillate (amplitude " + core::short_number(smooth_stress_amplitude) +
                     " MPa at a level of " + core::short_number(std::max(std::abs(sigma_max), std::abs(sigma_min))) +
                     " MPa, modulus " + core::short_number(smooth_stress_amplitude / smooth_strain_amplitude) +
                     " MPa)");
  r.stress_amplitude_MPa = smooth_stress_amplitude / gain;
  r.strain_amplitude = smooth_strain_amplitude / gain;
  r.mean_stress_MPa = 0.5 * (sigma_max + sigma_min);
  r.mean_strain = 0.5 * (eps_max + eps_min);
}

// Steps 3–7 on the period starting at `start`.
PeriodResult analyse_period(const SmoothSignals& x, double start, const WaveformReport& report,
                            double tolerance_s) {
  const double period_s = 1.0 / report.frequency_Hz, omega = kTwoPi * report.frequency_Hz;
  const int degree = report.harmonics;
  const double gain = report.smoothing_gain;
  std::vector<double> theta, sigma_k, eps_k;
  for (std::size_t i = 0; i < x.t.size(); ++i)
    if (x.t[i] >= start - tolerance_s && x.t[i] <= start + period_s + tolerance_s) {
      theta.push_back(omega * (x.t[i] - start));
      sigma_k.push_back(x.sigma[i]);
      eps_k.push_back(x.eps[i]);
    }
  const Eigen::Index m = static_cast<Eigen::Index>(theta.size());
  const auto qr = trig::trig_basis(theta, degree).colPivHouseholderQr();
  const TrigSeries s = trig::series_from(qr.solve(Eigen::Map<const Eigen::VectorXd>(sigma_k.data(), m)), degree);
  const TrigSeries e = trig::series_from(qr.solve(Eigen::Map<const Eigen::VectorXd>(eps_k.data(), m)), degree);

  PeriodResult r;
  r.start_s = start;
  r.samples = static_cast<int>(m);
  double smooth_stress_amplitude = 0.0, smooth_strain_amplitude = 0.0;
  period_amplitudes(s, e, gain, r, smooth_stress_amplitude, smooth_strain_amplitude);
  // ∮σ dε over one cycle of the two polynomials.
  double loop = 0.0;
  for (int j = 0; j < degree; ++j) loop += (j + 1) * (s.a[j] * e.b[j] - s.b[j] * e.a[j]);
  const double sin_delta = loop / (smooth_stress_amplitude * smooth_strain_amplitude);
  r.loss_energy_MPa = core::kPi * loop / (gain * gain);
  if (std::abs(sin_delta) > 1.0 + 1e-9)
    throw InputError("loop area exceeds pi * stress amplitude * strain amplitude (sin delta = " +
                     core::format_number(sin_delta, 6) + "): not a sinusoidal response");
  r.loss_angle_rad = std::asin(std::clamp(sin_delta, -1.0, 1.0));
  const double abs_modulus_MPa = r.stress_amplitude_MPa / r.strain_amplitude;
  r.storage_MPa = abs_modulus_MPa * std::cos(r.loss_angle_rad);
  r.loss_MPa = abs_modulus_MPa * std::sin(r.loss_angle_rad);
  double sigma_sq = 0.0, eps_sq = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double radius = std::hypot(eps_k[i] - r.mean_strain, e.slope(theta[i]));
    r.circle_deviation = std::max(r.circle_deviation, std::abs(radius - smooth_strain_amplitude) /
                                                          smooth_strain_amplitude);
    sigma_sq += std::pow(sigma_k[i] - s.value(theta[i]), 2);
    eps_sq += std::pow(eps_k[i] - e.value(theta[i]), 2);
  }
  r.fit_residual = std::max(std::sqrt(sigma_sq / m) / std::max(smooth_stress_amplitude, 1e-300),
                            std::sqrt(eps_sq / m) / smooth_strain_amplitude);
  return r;
}

// The means over the periods (what the thesis reports) and their standard deviations.
void summarise_periods(const WaveformOptions& options, WaveformReport& report) {
  const auto& p = report.periods;
  report.storage_MPa = mean_of(p, &PeriodResult::storage_MPa);
  report.loss_MPa = mean_of(p, &PeriodResult::loss_MPa);
  report.loss_angle_deg = mean_of(p, &PeriodResult::loss_angle_rad) * 180.0 / core::kPi;
  report.tan_delta = report.loss_MPa / report.storage_MPa;
  report.storage_std_MPa = std_of(p, &PeriodResult::storage_MPa);
  report.loss_std_MPa = std_of(p, &PeriodResult::loss_MPa);
  report.loss_angle_std_deg = std_of(p, &PeriodResult::loss_angle_rad) * 180.0 / core::kPi;
  report.stress_amplitude_MPa = mean_of(p, &PeriodResult::stress_amplitude_MPa);
  report.strain_amplitude = mean_of(p, &PeriodResult::strain_amplitude);
  report.mean_stress_MPa = mean_of(p, &PeriodResult::mean_stress_MPa);
  report.mean_strain = mean_of(p, &PeriodResult::mean_strain);
  report.loss_energy_MPa = mean_of(p, &PeriodResult::loss_energy_MPa);
  report.has_mean_modulus =
      std::abs(report.mean_strain) >= options.mean_strain_threshold * report.strain_amplitude &&
      report.mean_strain != 0.0;
  if (report.has_mean_modulus) report.mean_modulus_MPa = report.mean_stress_MPa / report.mean_strain;
  for (const auto& r : p) {
    report.max_circle_deviation = std::max(report.max_circle_deviation, r.circle_deviation);
    report.max_fit_residual = std::max(report.max_fit_residual, r.fit_residual);
  }
}

}  // namespace

WaveformReport analyse_waveform(const std::vector<double>& time_s,
                                const std::vector<double>& stress_MPa,
                                const std::vector<double>& strain, const WaveformOptions& options) {
  check_options(options);
  check_signals(time_s, stress_MPa, strain);
  WaveformReport report;
  const double dt = mean_time_step(time_s, report.warnings);
  find_frequency(time_s, strain, options, dt, report);
  choose_smoothing(options, dt, report);
  const int window = report.smoothing_window;
  const SmoothSignals x{moving_average(time_s, window), moving_average(stress_MPa, window),
                        moving_average(strain, window)};
  // Step 3: the last `periods` whole periods of the usable record.
  const double period_s = 1.0 / report.frequency_Hz;
  const double span_s = x.t.empty() ? 0.0 : x.t.back() - x.t.front();
  if (span_s < options.periods * period_s * (1.0 - 1e-9))
    throw InputError("record holds " + core::format_number(span_s / period_s, 4) +
                     " periods after smoothing; " + std::to_string(options.periods) +
                     " whole periods are needed");
  for (int k = 0; k < options.periods; ++k)
    report.periods.push_back(analyse_period(x, x.t.back() - (options.periods - k) * period_s,
                                            report, 1e-9 * dt));
  summarise_periods(options, report);
  check_report_finite(report);
  return report;
}

WaveformReport analyse_record(const WaveformRecord& record, const WaveformOptions& options) {
  try {
    return analyse_waveform(record.time_s, record.stress_MPa, record.strain, options);
  } catch (const InputError& e) {
    throw InputError(e.detail(), record.source_file, e.line(), e.column(), e.key());
  } catch (const core::NumericalError& e) {
    throw core::NumericalError(record.source_file + ": " + e.what());
  }
}

}  // namespace fitlib::data
