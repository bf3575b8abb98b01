// Isotropic linear viscoelastic material point in 3-D (docs/model.md §"Linear viscoelastic
// point"): generalized Maxwell series for the deviatoric and the volumetric part, the recurrence
// exact for strain linear in (reduced) time over each step.
#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"
#include "points.hpp"

namespace fitlib::model::points {
namespace {

// (1 − e^{−x})/x without cancellation for small x.
double one_minus_exp_over(double x) { return x < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x; }

// Deviatoric tensor components (Voigt order, shears as ε_ij) and the volume strain.
void split(const double* strain, double e[6], double& volume) {
  volume = strain[0] + strain[1] + strain[2];
  for (int i = 0; i < 3; ++i) e[i] = strain[i] - volume / 3.0;
  for (int i = 3; i < 6; ++i) e[i] = 0.5 * strain[i];
}

std::complex<double> complex_modulus(const MaxwellSeries& s, double omega) {
  std::complex<double> m = s.relaxed;
  for (size_t i = 0; i < s.moduli.size(); ++i) {
    const std::complex<double> iwt(0.0, omega * s.times_s[i]);
    m += s.moduli[i] * iwt / (1.0 + iwt);
  }
  return m;
}

void check_series(const MaxwellSeries& s, const std::string& what) {
  if (s.moduli.size() != s.times_s.size())
    throw core::UsageError(what + " series: moduli and times differ in length");
  for (double t : s.times_s)
    if (!(t > 0.0) || !std::isfinite(t))
      throw core::UsageError(what + " series: relaxation times must be finite and > 0");
}

// State: ε_n (6), deviatoric Maxwell stresses h_i (6 per shear term, σ_ij components, without
// the temperature scale), volumetric Maxwell pressures q_j (one per bulk term).
class ViscoelasticPoint final : public MaterialPoint {
 public:
  ViscoelasticPoint(MaxwellSeries shear, MaxwellSeries bulk, TemperatureFunction temperature,
                    std::string description)
      : shear_(std::move(shear)), bulk_(std::move(bulk)), temperature_(std::move(temperature)),
        description_(std::move(description)) {
    check_series(shear_, description_ + ": shear");
    check_series(bulk_, description_ + ": bulk");
  }
  std::string describe() const override { return description_; }
  std::size_t state_size() const override { return 6 + 6 * shear_.moduli.size() + bulk_.moduli.size(); }
  std::vector<double> initial_state() const override { return std::vector<double>(state_size(), 0.0); }

  Vector6 update(const double* state, const Vector6& strain, double dt_s, double temperature_C,
                 double* next, Matrix6* tangent) const override {
    if (!(dt_s >= 0.0) || !std::isfinite(dt_s))
      throw core::UsageError(description_ + ": the time step must be finite and ≥ 0");
    const TemperatureFactors f = temperature_(temperature_C);
    const double dxi = dt_s / f.shift_factor;  // reduced time increment
    double e[6], e_n[6], theta, theta_n;
    split(strain.data(), e, theta);
    split(state, e_n, theta_n);
    double s[6], G_eff = shear_.relaxed, K_eff = bulk_.relaxed;
    for (int k = 0; k < 6; ++k) s[k] = 2.0 * shear_.relaxed * e[k];
    const double* h = state + 6;
    double* h_next = next + 6;
    for (size_t i = 0; i < shear_.moduli.size(); ++i) {
      const double x = dxi / shear_.times_s[i], decay = std::exp(-x);
      const double gain = shear_.moduli[i] * one_minus_exp_over(x);
      G_eff += gain;
      for (int k = 0; k < 6; ++k) {
        h_next[6 * i + k] = decay * h[6 * i + k] + 2.0 * gain * (e[k] - e_n[k]);
        s[k] += h_next[6 * i + k];
      }
    }
    double pressure = bulk_.relaxed * theta;
    const double* q = h + 6 * shear_.moduli.size();
    double* q_next = h_next + 6 * shear_.moduli.size();
    for (size_t j = 0; j < bulk_.moduli.size(); ++j) {
      const double x = dxi / bulk_.times_s[j];
      const double gain = bulk_.moduli[j] * one_minus_exp_over(x);
      K_eff += gain;
      q_next[j] = std::exp(-x) * q[j] + gain * (theta - theta_n);
      pressure += q_next[j];
    }
    for (int k = 0; k < 6; ++k) next[k] = strain[k];
    Vector6 sigma;
    for (int k = 0; k < 6; ++k) sigma[k] = f.scale * (s[k] + (k < 3 ? pressure : 0.0));
    if (tangent) *tangent = f.scale * isotropic_stiffness(K_eff, G_eff);
    return sigma;
  }

  ComplexMatrix6 complex_stiffness(double frequency_Hz, double temperature_C) const override {
    const TemperatureFactors f = temperature_(temperature_C);
    const double omega = core::angular_frequency(frequency_Hz) * f.shift_factor;
    return std::complex<double>(f.scale) *
           isotropic_stiffness(complex_modulus(bulk_, omega), complex_modulus(shear_, omega));
  }

 private:
  MaxwellSeries shear_, bulk_;
  TemperatureFunction temperature_;
  std::string description_;
};

}  // namespace

MaterialPointPtr linear_viscoelastic_point(MaxwellSeries shear, MaxwellSeries bulk,
                                           TemperatureFunction temperature,
                                           std::string description) {
  return std::make_shared<ViscoelasticPoint>(std::move(shear), std::move(bulk),
                                             std::move(temperature), std::move(description));
}

}  // namespace fitlib::model::points
