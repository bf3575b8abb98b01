// Waveform analysis by the energy method (Report V §4.8); see waveform.hpp for the method.
#include "fitlib/data/waveform.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::data {
namespace {

using core::InputError;
constexpr double kTwoPi = 2.0 * core::kPi;

// Trigonometric polynomial p(θ) = c + Σ_{k=1..K} a_k cos kθ + b_k sin kθ, θ = ω (t − t0).
struct TrigSeries {
  double c = 0.0;
  Eigen::VectorXd a, b;  // index k−1
  int degree() const { return static_cast<int>(a.size()); }
  double value(double theta) const {
    double v = c;
    for (int k = 1; k <= degree(); ++k) v += a[k - 1] * std::cos(k * theta) + b[k - 1] * std::sin(k * theta);
    return v;
  }
  // dp/dθ and d²p/dθ².
  double slope(double theta) const {
    double v = 0.0;
    for (int k = 1; k <= degree(); ++k) v += k * (b[k - 1] * std::cos(k * theta) - a[k - 1] * std::sin(k * theta));
    return v;
  }
  double curvature(double theta) const {
    double v = 0.0;
    for (int k = 1; k <= degree(); ++k) v -= k * k * (a[k - 1] * std::cos(k * theta) + b[k - 1] * std::sin(k * theta));
    return v;
  }
};

// Columns 1, cos kθ, sin kθ (k = 1..K) at the given phases.
Eigen::MatrixXd trig_basis(const std::vector<double>& theta, int degree) {
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(theta.size()), 2 * degree + 1);
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    basis(row, 0) = 1.0;
    for (int k = 1; k <= degree; ++k) {
      basis(row, 2 * k - 1) = std::cos(k * theta[i]);
      basis(row, 2 * k) = std::sin(k * theta[i]);
    }
  }
  return basis;
}

TrigSeries series_from(const Eigen::VectorXd& coefficients, int degree) {
  TrigSeries s;
  s.c = coefficients[0];
  s.a.resize(degree);
  s.b.resize(degree);
  for (int k = 1; k <= degree; ++k) {
    s.a[k - 1] = coefficients[2 * k - 1];
    s.b[k - 1] = coefficients[2 * k];
  }
  return s;
}

// Largest and smallest value of a trigonometric polynomial over one period: a dense scan, then
// Newton steps on p′ = 0 from the best grid points.
std::pair<double, double> extremes(const TrigSeries& p) {
  const int grid = std::max(256, 32 * p.degree());
  int i_max = 0, i_min = 0;
  double v_max = -HUGE_VAL, v_min = HUGE_VAL;
  for (int i = 0; i < grid; ++i) {
    const double v = p.value(kTwoPi * i / grid);
    if (v > v_max) v_max = v, i_max = i;
    if (v < v_min) v_min = v, i_min = i;
  }
  const auto polish = [&](int start, double best, bool is_max) {
    double theta = kTwoPi * start / grid;
    for (int iteration = 0; iteration < 20; ++iteration) {
      const double curvature = p.curvature(theta);
      if (curvature == 0.0 || (is_max ? curvature > 0.0 : curvature < 0.0)) break;
      const double step = p.slope(theta) / curvature;
      theta -= std::clamp(step, -kTwoPi / grid, kTwoPi / grid);
      const double v = p.value(theta);
      best = is_max ? std::max(best, v) : std::min(best, v);
      if (std::abs(step) < 1e-15) break;
    }
    return best;
  };
  return {polish(i_max, v_max, true), polish(i_min, v_min, false)};
}

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

// Gauss–Newton fit of c + Σ a_k cos kω(t−t0) + b_k sin kω(t−t0) to the whole record, over
// the coefficients and ω together; returns the refined ω (exact for an exact trig polynomial).
double refine_angular_frequency(const std::vector<double>& time_s, const std::vector<double>& y,
                                double omega, int degree, std::vector<std::string>& warnings) {
  const double t0 = 0.5 * (time_s.front() + time_s.back());
  const Eigen::Index n = static_cast<Eigen::Index>(y.size());
  const Eigen::Map<const Eigen::VectorXd> observed(y.data(), n);
  const auto phases = [&](double w) {
    std::vector<double> theta(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) theta[i] = w * (time_s[i] - t0);
    return theta;
  };
  const double omega_start = omega;
  Eigen::VectorXd coefficients =
      trig_basis(phases(omega), degree).colPivHouseholderQr().solve(observed);
  for (int iteration = 0; iteration < 50; ++iteration) {
    const std::vector<double> theta = phases(omega);
    Eigen::MatrixXd jacobian(n, 2 * degree + 2);
    jacobian.leftCols(2 * degree + 1) = trig_basis(theta, degree);
    const TrigSeries p = series_from(coefficients, degree);
    for (Eigen::Index i = 0; i < n; ++i)
      jacobian(i, 2 * degree + 1) = (time_s[i] - t0) * p.slope(theta[i]);
    const Eigen::VectorXd residual = observed - jacobian.leftCols(2 * degree + 1) * coefficients;
    const Eigen::VectorXd step = jacobian.colPivHouseholderQr().solve(residual);
    coefficients += step.head(2 * degree + 1);
    omega += step[2 * degree + 1];
    if (std::abs(step[2 * degree + 1]) <= 1e-15 * omega) break;
  }
  if (!(std::abs(omega / omega_start - 1.0) < 0.05)) {
    warnings.push_back("frequency refinement did not converge; zero-crossing estimate used");
    return omega_start;
  }
  return omega;
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

}  // namespace

WaveformReport analyse_waveform(const std::vector<double>& time_s,
                                const std::vector<double>& stress_MPa,
                                const std::vector<double>& strain, const WaveformOptions& options) {
  if (options.periods < 1) throw core::UsageError("waveform: periods must be at least 1");
  if (options.harmonics < 1) throw core::UsageError("waveform: harmonics must be at least 1");
  if (options.smoothing_window < 0 || (options.smoothing_window > 0 && options.smoothing_window % 2 == 0))
    throw core::UsageError("waveform: smoothing window must be an odd number of samples (1 = off)");
  check_signals(time_s, stress_MPa, strain);
  WaveformReport report;
  const std::size_t n = time_s.size();
  const double dt = (time_s.back() - time_s.front()) / static_cast<double>(n - 1);
  double max_step_deviation = 0.0;
  for (std::size_t i = 1; i < n; ++i)
    max_step_deviation = std::max(max_step_deviation, std::abs(time_s[i] - time_s[i - 1] - dt));
  if (max_step_deviation > 1e-3 * dt)
    report.warnings.push_back("irregular sampling (time step varies by up to " +
                              std::to_string(100.0 * max_step_deviation / dt) +
                              " %); the moving average assumes uniform steps");

  // 1. Frequency: zero crossings, then a least-squares refinement on the whole strain record.
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
    frequency_Hz = refine_angular_frequency(time_s, strain, kTwoPi * frequency_Hz, degree,
                                            report.warnings) / kTwoPi;
  samples_per_period = 1.0 / (frequency_Hz * dt);
  const double omega = kTwoPi * frequency_Hz;
  const double period_s = 1.0 / frequency_Hz;

  // 2. Smoothing, same window on both signals (and time, to keep the samples aligned).
  int window = options.smoothing_window;
  if (window == 0) {
    window = static_cast<int>(samples_per_period * options.smoothing_period_fraction);
    if (window % 2 == 0) --window;
    window = std::max(1, window);
  }
  const std::vector<double> t = moving_average(time_s, window);
  const std::vector<double> sigma = moving_average(stress_MPa, window);
  const std::vector<double> eps = moving_average(strain, window);
  report.frequency_Hz = frequency_Hz;
  report.samples_per_period = samples_per_period;
  report.smoothing_window = window;
  // Gain of the moving average at the fundamental; amplitudes and W are divided by it (W by its
  // square) so that a sinusoid is reported at its true size. Ratios (E′, E″, δ) need no correction.
  const double half_step = 0.5 * omega * dt;
  report.smoothing_gain = window == 1 ? 1.0 : std::sin(window * half_step) / (window * std::sin(half_step));
  const double gain = report.smoothing_gain;
  report.harmonics = degree;

  // 3. The last `periods` whole periods of the usable record.
  const double span_s = t.empty() ? 0.0 : t.back() - t.front();
  if (span_s < options.periods * period_s * (1.0 - 1e-9))
    throw InputError("record holds " + std::to_string(span_s / period_s) +
                     " periods after smoothing; " + std::to_string(options.periods) +
                     " whole periods are needed");
  const double tolerance_s = 1e-9 * dt;
  for (int k = 0; k < options.periods; ++k) {
    const double start = t.back() - (options.periods - k) * period_s;
    std::vector<double> theta, sigma_k, eps_k;
    for (std::size_t i = 0; i < t.size(); ++i)
      if (t[i] >= start - tolerance_s && t[i] <= start + period_s + tolerance_s) {
        theta.push_back(omega * (t[i] - start));
        sigma_k.push_back(sigma[i]);
        eps_k.push_back(eps[i]);
      }
    const Eigen::Index m = static_cast<Eigen::Index>(theta.size());
    const auto qr = trig_basis(theta, degree).colPivHouseholderQr();
    const TrigSeries s = series_from(qr.solve(Eigen::Map<const Eigen::VectorXd>(sigma_k.data(), m)), degree);
    const TrigSeries e = series_from(qr.solve(Eigen::Map<const Eigen::VectorXd>(eps_k.data(), m)), degree);

    PeriodResult r;
    r.start_s = start;
    r.samples = static_cast<int>(m);
    const auto [sigma_max, sigma_min] = extremes(s);
    const auto [eps_max, eps_min] = extremes(e);
    const double smooth_stress_amplitude = 0.5 * (sigma_max - sigma_min);
    const double smooth_strain_amplitude = 0.5 * (eps_max - eps_min);
    if (!(smooth_strain_amplitude > 0.0)) throw InputError("strain amplitude is zero in a period");
    if (!(smooth_stress_amplitude > 0.0)) throw InputError("stress amplitude is zero in a period");
    // 1e12 MPa is far above any solid (steel: 2e5 MPa): beyond it the strain signal is noise.
    if (!(smooth_stress_amplitude / smooth_strain_amplitude <= 1e12))
      throw InputError("stress amplitude / strain amplitude is not a plausible modulus (strain amplitude " +
                       core::short_number(smooth_strain_amplitude) + ")");
    r.stress_amplitude_MPa = smooth_stress_amplitude / gain;
    r.strain_amplitude = smooth_strain_amplitude / gain;
    r.mean_stress_MPa = 0.5 * (sigma_max + sigma_min);
    r.mean_strain = 0.5 * (eps_max + eps_min);
    // ∮σ dε over one cycle of the two polynomials.
    double loop = 0.0;
    for (int j = 0; j < degree; ++j) loop += (j + 1) * (s.a[j] * e.b[j] - s.b[j] * e.a[j]);
    const double sin_delta = loop / (smooth_stress_amplitude * smooth_strain_amplitude);
    r.loss_energy_MPa = core::kPi * loop / (gain * gain);
    if (std::abs(sin_delta) > 1.0 + 1e-9)
      throw InputError("loop area exceeds pi * stress amplitude * strain amplitude (sin delta = " +
                       std::to_string(sin_delta) + "): not a sinusoidal response");
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
    report.periods.push_back(r);
  }

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
  check_report_finite(report);
  return report;
}

void stress_strain_from_force(const SpecimenInfo& specimen, const std::vector<double>& force_N,
                              const std::vector<double>& displacement_mm,
                              std::vector<double>& stress_MPa, std::vector<double>& strain) {
  const auto require = [](double value, const char* key) {
    if (!(value > 0.0))
      throw InputError(std::string("specimen ") + key +
                           " must be given and positive for force/displacement input",
                       "", 0, 0, key);
    return value;
  };
  if (!specimen.has_mode) throw InputError("specimen mode is required", "", 0, 0, "mode");
  if (specimen.n_specimens < 1)
    throw InputError("n_specimens must be at least 1", "", 0, 0, "n_specimens");
  const double area_mm2 = require(specimen.area_mm2, "area_mm2");
  double force_to_stress = 0.0, displacement_to_strain = 0.0;
  switch (specimen.mode) {
    case model::TestMode::shear:  // τ = F/(n·A), γ = u/h (each sandwich layer sees u)
      force_to_stress = 1.0 / (specimen.n_specimens * area_mm2);
      displacement_to_strain = 1.0 / require(specimen.thickness_mm, "thickness_mm");
      break;
    case model::TestMode::uniaxial:  // σ = F/(n·A), ε = u/L
      force_to_stress = 1.0 / (specimen.n_specimens * area_mm2);
      displacement_to_strain = 1.0 / require(specimen.length_mm, "length_mm");
      break;
    case model::TestMode::bulk:  // p = F/A on the piston, ε_v = ΔV/V0 = A·u/V0
      force_to_stress = 1.0 / area_mm2;
      displacement_to_strain = area_mm2 / require(specimen.volume_mm3, "volume_mm3");
      break;
  }
  stress_MPa.resize(force_N.size());
  strain.resize(displacement_mm.size());
  for (std::size_t i = 0; i < force_N.size(); ++i) stress_MPa[i] = force_N[i] * force_to_stress;
  for (std::size_t i = 0; i < displacement_mm.size(); ++i)
    strain[i] = displacement_mm[i] * displacement_to_strain;
}

namespace {

enum class KeyKind { text, number, count, mode };
const std::map<std::string, KeyKind>& metadata_keys() {
  static const std::map<std::string, KeyKind> keys = {
      {"mode", KeyKind::mode},           {"area_mm2", KeyKind::number},
      {"thickness_mm", KeyKind::number}, {"length_mm", KeyKind::number},
      {"volume_mm3", KeyKind::number},   {"n_specimens", KeyKind::count},
      {"temperature_C", KeyKind::number}, {"material", KeyKind::text},
      {"specimen", KeyKind::text},       {"orientation", KeyKind::text}};
  return keys;
}

using ErrorAt = std::function<InputError(const std::string& message)>;
constexpr int kMaxSpecimens = 1000;  // specimens loaded in parallel (2 in a double sandwich)

void apply_metadata(SpecimenInfo& info, const std::string& key, const nlohmann::json& value,
                    const ErrorAt& error) {
  const auto it = metadata_keys().find(key);
  if (it == metadata_keys().end())
    throw error("unknown specimen key '" + key +
                "' (known: mode, area_mm2, thickness_mm, length_mm, volume_mm3, n_specimens, "
                "temperature_C, material, specimen, orientation)");
  const KeyKind kind = it->second;
  if (kind == KeyKind::number || kind == KeyKind::count) {
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      throw error("'" + key + "' must be a finite number");
  } else if (!value.is_string()) {
    throw error("'" + key + "' must be a string");
  }
  if (kind == KeyKind::mode) {
    const auto mode = model::test_mode_from_label(value.get<std::string>());
    if (!mode)
      throw error("unknown test mode '" + value.get<std::string>() + "' (expected " + kModeLabels + ")");
    info.mode = *mode;
    info.has_mode = true;
  } else if (kind == KeyKind::count) {
    const double count = value.get<double>();
    if (count < 1.0 || count > kMaxSpecimens || count != std::floor(count))
      throw error("'n_specimens' must be a whole number from 1 to " + std::to_string(kMaxSpecimens));
    info.n_specimens = static_cast<int>(count);
  } else if (kind == KeyKind::number) {
    const double number = value.get<double>();
    if (key == "area_mm2") info.area_mm2 = number;
    if (key == "thickness_mm") info.thickness_mm = number;
    if (key == "length_mm") info.length_mm = number;
    if (key == "volume_mm3") info.volume_mm3 = number;
    if (key == "temperature_C") info.temperature_C = number;
  } else {
    const std::string text = value.get<std::string>();
    if (key == "material") info.material = text;
    if (key == "specimen") info.specimen = text;
    if (key == "orientation") {
      static const char* kOrientations[] = {"11", "22", "33", "12", "13", "23", "3232", "2332"};
      if (std::find(std::begin(kOrientations), std::end(kOrientations), text) == std::end(kOrientations))
        throw error("unknown orientation '" + text + "' (expected 11, 22, 33, 12, 13, 23, 3232 or 2332)");
      info.orientation = text;
    }
  }
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// `# key = value` with key an identifier ([A-Za-z_][A-Za-z0-9_]*); other comments are free text.
// A plain scan, linear in the line length (a regular expression recursed per character).
bool parse_metadata_line(const std::string& text, std::string& key, std::string& value) {
  const auto is_start = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  const auto is_part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  const auto skip_space = [&](std::size_t i) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    return i;
  };
  std::size_t i = skip_space(0);
  if (i == text.size() || text[i] != '#') return false;
  i = skip_space(i + 1);
  if (i == text.size() || !is_start(text[i])) return false;
  const std::size_t key_begin = i;
  while (i < text.size() && is_part(text[i])) ++i;
  key = text.substr(key_begin, i - key_begin);
  i = skip_space(i);
  if (i == text.size() || text[i] != '=') return false;
  value = text.substr(i + 1);
  return true;
}

}  // namespace

WaveformRecord read_waveform(const std::string& signals_path, const std::string& sidecar_path) {
  WaveformRecord record;
  record.source_file = signals_path;
  const std::string bytes = core::read_file(signals_path);
  record.source_sha256 = core::sha256_hex(bytes);
  const std::vector<CsvLine> lines = split_csv_lines(bytes, signals_path);

  // Metadata from `# key = value` lines.
  nlohmann::json metadata = nlohmann::json::object();
  std::size_t next = 0;
  for (const auto& line : lines) {
    std::string key, raw_value;
    if (!is_blank_or_comment(line.text) || !parse_metadata_line(line.text, key, raw_value)) continue;
    std::string value_text = trim(raw_value);
    if (value_text.size() >= 2 && value_text.front() == '"' && value_text.back() == '"')
      value_text = value_text.substr(1, value_text.size() - 2);
    const auto error = [&](const std::string& message) {
      return InputError(message, signals_path, line.number, 0, key);
    };
    const auto kind = metadata_keys().find(key);
    nlohmann::json value = value_text;
    if (kind != metadata_keys().end() &&
        (kind->second == KeyKind::number || kind->second == KeyKind::count))
      value = parse_csv_number(value_text, key, signals_path, line.number, 0);
    if (metadata.contains(key) && metadata[key] != value) throw error("given twice with different values");
    apply_metadata(record.specimen, key, value, error);
    metadata[key] = value;
  }
  if (!sidecar_path.empty()) {
    const nlohmann::json sidecar = core::load_json(sidecar_path);
    if (!sidecar.is_object()) throw InputError("specimen sidecar must be a JSON object", sidecar_path);
    for (const auto& [key, value] : sidecar.items()) {
      const auto error = [&, key = key](const std::string& message) {
        return InputError(message, sidecar_path, 0, 0, key);
      };
      if (metadata.contains(key) &&
          !(metadata[key] == value ||
            (value.is_number() && metadata[key].is_number() && metadata[key].get<double>() == value.get<double>())))
        throw error("differs from the '# " + key + " = ...' line of " + signals_path);
      apply_metadata(record.specimen, key, value, error);
    }
  }

  // Signals.
  while (next < lines.size() && is_blank_or_comment(lines[next].text)) ++next;
  if (next == lines.size())
    throw InputError("no header row (empty file)", signals_path, static_cast<int>(lines.size()) + 1);
  const CsvLine& header = lines[next++];
  const std::vector<std::string> names = split_csv_fields(header.text, signals_path, header.number);
  static const char* kColumns[] = {"time_s", "force_N", "displacement_mm", "stress_MPa", "strain"};
  int column_of[5] = {-1, -1, -1, -1, -1};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int column = static_cast<int>(i) + 1;
    if (names[i].rfind("x_", 0) == 0) continue;
    const auto known = std::find_if(std::begin(kColumns), std::end(kColumns),
                                    [&](const char* c) { return names[i] == c; });
    if (known == std::end(kColumns))
      throw InputError("unknown column '" + names[i] +
                           "' (expected time_s and force_N, displacement_mm or stress_MPa, strain)",
                       signals_path, header.number, column);
    int& slot = column_of[known - std::begin(kColumns)];
    if (slot >= 0) throw InputError("duplicate column '" + names[i] + "'", signals_path, header.number, column);
    slot = static_cast<int>(i);
  }
  const bool force_input = column_of[1] >= 0 || column_of[2] >= 0;
  const bool stress_input = column_of[3] >= 0 || column_of[4] >= 0;
  const auto missing = [&](const std::string& what) {
    return InputError("missing required column " + what, signals_path, header.number);
  };
  if (column_of[0] < 0) throw missing("'time_s'");
  if (force_input && stress_input)
    throw InputError("give either force_N, displacement_mm or stress_MPa, strain, not both",
                     signals_path, header.number);
  if (!stress_input && (column_of[1] < 0 || column_of[2] < 0))
    throw missing(column_of[1] < 0 ? "'force_N'" : "'displacement_mm'");
  if (stress_input && (column_of[3] < 0 || column_of[4] < 0))
    throw missing(column_of[3] < 0 ? "'stress_MPa'" : "'strain'");
  const int load_column = force_input ? column_of[1] : column_of[3];
  const int motion_column = force_input ? column_of[2] : column_of[4];

  std::vector<double> load, motion;
  for (; next < lines.size(); ++next) {
    const CsvLine& line = lines[next];
    if (is_blank_or_comment(line.text)) continue;
    const std::vector<std::string> fields = split_csv_fields(line.text, signals_path, line.number);
    if (fields.size() != names.size())
      throw InputError("row has " + std::to_string(fields.size()) + " fields, header has " +
                           std::to_string(names.size()),
                       signals_path, line.number, static_cast<int>(std::min(fields.size(), names.size())) + 1);
    const auto number = [&](int column) {
      return parse_csv_number(fields[column], names[column], signals_path, line.number, column + 1);
    };
    const double t = number(column_of[0]);
    if (!record.time_s.empty() && !(t > record.time_s.back()))
      throw InputError("time_s is not increasing", signals_path, line.number, column_of[0] + 1);
    record.time_s.push_back(t);
    load.push_back(number(load_column));
    motion.push_back(number(motion_column));
  }
  if (record.time_s.empty()) throw InputError("no data rows after the header", signals_path, header.number);
  if (!record.specimen.has_mode)
    throw InputError("specimen mode is required ('# mode = shear' or the sidecar)", signals_path, 0, 0, "mode");
  if (force_input) {
    try {
      stress_strain_from_force(record.specimen, load, motion, record.stress_MPa, record.strain);
    } catch (const InputError& e) {
      throw InputError(e.detail(), sidecar_path.empty() ? signals_path : sidecar_path, 0, 0, e.key());
    }
  } else {
    record.stress_MPa = std::move(load);
    record.strain = std::move(motion);
  }
  return record;
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

DynamicTestRow waveform_row(const WaveformReport& report, const SpecimenInfo& specimen,
                            const std::string& source_file) {
  if (report.loss_MPa < 0.0)
    throw InputError("negative loss modulus from the energy method (stress lags strain): check "
                     "the signs of the force and displacement signals",
                     source_file);
  DynamicTestRow row;
  auto& c = row.condition;
  c.mode = specimen.mode;
  c.orientation = specimen.orientation;
  c.frequency_Hz = report.frequency_Hz;
  c.temperature_C = specimen.temperature_C;
  c.strain_amplitude = report.strain_amplitude;
  c.mean_strain = report.mean_strain;
  row.storage_MPa = report.storage_MPa;
  row.loss_MPa = report.loss_MPa;
  row.has_mean_modulus = report.has_mean_modulus;
  row.mean_modulus_MPa = report.mean_modulus_MPa;
  row.material = specimen.material;
  row.specimen = specimen.specimen;
  row.source_file = source_file;
  return row;
}

}  // namespace fitlib::data
