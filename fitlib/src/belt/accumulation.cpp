#include "fitlib/belt/accumulation.hpp"

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::InputError;
using core::kPi;

void check_loading(double omega, double kappa) {
  if (!(omega > 0.0) || !std::isfinite(omega))
    throw InputError("angular velocity must be positive", {}, 0, 0, "accumulation.omega_rad_s");
  if (!(kappa >= 0.0) || !std::isfinite(kappa))
    throw InputError("kappa = l/R must be >= 0", {}, 0, 0, "accumulation.kappa");
}
}  // namespace

void validate(const RetardationSpectrum& s, const std::string& key) {
  if (s.compliances.size() != s.times_s.size() || s.compliances.empty())
    throw InputError("spectrum needs as many retardation times as lines (and at least one)", {}, 0,
                     0, key);
  for (std::size_t i = 0; i < s.compliances.size(); ++i) {
    if (!(s.compliances[i] >= 0.0) || !std::isfinite(s.compliances[i]))
      throw InputError("spectrum line L_" + std::to_string(i + 1) + " must be >= 0", {}, 0, 0, key);
    if (!(s.times_s[i] > 0.0) || !std::isfinite(s.times_s[i]))
      throw InputError("retardation time lambda_" + std::to_string(i + 1) + " must be > 0", {}, 0,
                       0, key);
  }
}

std::vector<std::string> spectrum_shape_names() {
  return {"box", "gauss", "lorentzian", "ramp", "wedge"};
}

RetardationSpectrum spectrum_shape(const std::string& name, double total, int per_decade,
                                   double J_g) {
  auto envelope = [&](double x) -> double {  // x = log10 λ
    if (name == "box") return std::abs(x) <= 4.0 ? 1.0 : 0.0;
    if (name == "gauss") return std::exp(-x * x / (2 * 0.25));
    if (name == "lorentzian") return 1.0 / (1.0 + x * x / 0.25);
    if (name == "ramp") return x < 0.0 ? (x + 6.0) / 6.0 : 1.0;
    if (name == "wedge") return (6.0 - x) / 12.0;
    throw InputError("unknown spectrum shape '" + name +
                         "' (box, gauss, lorentzian, ramp, wedge)", {}, 0, 0, "spectrum");
  };
  if (per_decade < 1) throw InputError("lines per decade must be >= 1", {}, 0, 0, "spectrum");
  RetardationSpectrum s;
  s.glassy_compliance = J_g;
  double sum = 0.0;
  for (int k = -6 * per_decade; k <= 6 * per_decade; ++k) {
    const double x = static_cast<double>(k) / per_decade;
    s.times_s.push_back(std::pow(10.0, x));
    s.compliances.push_back(envelope(x));
    sum += s.compliances.back();
  }
  for (double& L : s.compliances) L *= total / sum;
  return s;
}

double accumulated_strain(const RetardationSpectrum& s, double tau0, double N, double omega,
                          double kappa) {
  check_loading(omega, kappa);
  if (!(N >= 0.0)) throw InputError("cycle count must be >= 0", {}, 0, 0, "accumulation.cycles");
  double gamma = 0.0;
  for (std::size_t i = 0; i < s.compliances.size(); ++i) {
    const double a = 1.0 / (omega * s.times_s[i]);
    // Σ_{m=0}^{N−1} q^m with q = e^{−2a(κ+π)}: (1 − q^N)/(1 − q), written with expm1.
    const double b = -2.0 * a * (kappa + kPi);
    const double geometric = std::expm1(b * N) / std::expm1(b);
    gamma += s.compliances[i] * (-std::expm1(-kPi * a)) * std::exp(-a * kappa) * geometric;
  }
  return tau0 * gamma;
}

double accumulated_strain_direct_sum(const RetardationSpectrum& s, double tau0, long N,
                                     double omega, double kappa) {
  check_loading(omega, kappa);
  double gamma = 0.0;
  for (long n = 1; n <= N; ++n)
    for (std::size_t i = 0; i < s.compliances.size(); ++i) {
      const double wl = omega * s.times_s[i];
      gamma += s.compliances[i] * (1.0 - std::exp(-kPi / wl)) *
               std::exp(-((kappa + kPi) * (2.0 * (N - n) + 1.0) - kPi) / wl);
    }
  return tau0 * gamma;
}

double accumulated_strain_time_integration(const RetardationSpectrum& s, double tau0, long N,
                                           double omega, double kappa, int substeps) {
  check_loading(omega, kappa);
  // Kelvin element i: strain e_i with λ_i ė_i + e_i = L_i τ; exact update for constant τ.
  const std::size_t K = s.compliances.size();
  std::vector<double> e(K, 0.0);
  auto hold = [&](double tau, double duration) {
    const double h = duration / substeps;
    for (int k = 0; k < substeps; ++k)
      for (std::size_t i = 0; i < K; ++i) {
        const double target = s.compliances[i] * tau;
        e[i] = target + (e[i] - target) * std::exp(-h / s.times_s[i]);
      }
  };
  // Cycle: unloaded until t1 = (κ + π)/ω, loaded until t2 = (κ + 2π)/ω, unloaded until ξ.
  const double t1 = (kappa + kPi) / omega, t2 = (kappa + 2 * kPi) / omega, xi = 2 * (kappa + kPi) / omega;
  for (long n = 0; n < N; ++n) {
    hold(0.0, t1);
    hold(tau0, t2 - t1);
    hold(0.0, xi - t2);
  }
  double gamma = 0.0;  // τ = 0 at t = Nξ, so the glassy part is zero
  for (double ei : e) gamma += ei;
  return gamma;
}

long critical_cycles(const RetardationSpectrum& s, double tau0, double omega, double kappa,
                     double limit, long N_max) {
  if (accumulated_strain(s, tau0, static_cast<double>(N_max), omega, kappa) < limit) return -1;
  long lo = 0, hi = N_max;  // Γ(lo) < limit ≤ Γ(hi)
  while (hi - lo > 1) {
    const long mid = lo + (hi - lo) / 2;
    (accumulated_strain(s, tau0, static_cast<double>(mid), omega, kappa) >= limit ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace fitlib::belt
