// Fritzson's model in the time domain at one material point: backward Euler (or exponential)
// update, consistent tangent by forward-mode differentiation of the same code, running-mean
// strain, damage evolution; and a driver for the dynamic-test loadings.
#include "fitlib/model/fritzson_point.hpp"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/fritzson.hpp"
#include "fitlib/core/units.hpp"
#include "fritzson_contract.hpp"

namespace fitlib::model::fritzson {
namespace {

using core::kPi;
using Jet6 = ceres::Jet<double, 6>;

// Deviatoric tensor components (Voigt order, shear as ε_ij) of an engineering Voigt strain.
template <typename T>
void deviatoric(const T* strain, T* e) {
  const T mean = (strain[0] + strain[1] + strain[2]) / 3.0;
  for (int i = 0; i < 3; ++i) e[i] = strain[i] - mean;
  for (int i = 3; i < 6; ++i) e[i] = 0.5 * strain[i];
}

// One part's constants in the scalar type of the update (derivatives flow through h and g).
template <typename T>
std::array<T, kPartSize> part_as(const double* part) {
  std::array<T, kPartSize> out;
  for (int i = 0; i < kPartSize; ++i) out[i] = T(part[i]);
  return out;
}


// The step's deviatoric strains (tensor components), shared by the three deviatoric parts.
template <typename T>
struct StepStrains {
  T e[6];         // now
  double e_n[6];  // at the start of the step
  T e_osc[6];     // oscillating part (4.30)
};

// Running mean (4.29) and oscillating part (4.30). At t = 0 the mean is the strain itself
// (the limit of (1/t)∫e), so a jump at the start leaves e^o = 0.
template <typename T, typename Vec>
void running_mean(const Vec& integral_n, StepStrains<T>& k, double dt, double t_next,
                  Scheme scheme, T* integral) {
  for (int i = 0; i < 6; ++i) {
    integral[i] = scheme == Scheme::exponential
                      ? T(integral_n[i]) + 0.5 * dt * (k.e[i] + k.e_n[i])
                      : T(integral_n[i]) + dt * k.e[i];
    k.e_osc[i] = t_next > 0.0 ? k.e[i] - integral[i] / t_next : T(0.0);
  }
}

// Damage drivers (4.32, 4.77, 4.78) of I, A1, A2; shear components count twice in the norm.
template <typename T>
void oscillation_norms(const T* e_osc, T* osc) {
  osc[0] = safe_sqrt(e_osc[0] * e_osc[0] + e_osc[1] * e_osc[1] + e_osc[2] * e_osc[2] +
                     2.0 * (e_osc[3] * e_osc[3] + e_osc[4] * e_osc[4] + e_osc[5] * e_osc[5]));
  osc[1] = safe_sqrt(2.0 * e_osc[2] * e_osc[2]);
  osc[2] = safe_sqrt(2.0 * (e_osc[2] * e_osc[2] + e_osc[3] * e_osc[3] + e_osc[4] * e_osc[4]));
}

// Maxwell coefficients of one part's five elements: s_{n+1} = decay·s_n + gain·(2M h2 g2)·Δe.
struct MaxwellStep {
  double decay[5], gain[5];
};

MaxwellStep maxwell_step(const double* part, double dt, Scheme scheme) {
  MaxwellStep m;
  double times[5];
  maxwell_times(part[kTau], part[kK_ratio], times);
  for (int n = 0; n < 5; ++n) {
    const double x = dt / times[n];
    if (scheme == Scheme::exponential) {
      m.decay[n] = std::exp(-x);
      m.gain[n] = one_minus_exp_over(x);
    } else {
      m.decay[n] = 1.0 / (1.0 + x);
      m.gain[n] = m.decay[n];
    }
  }
  return m;
}

// Isotropic deviatoric part (4.40–4.50): writes s, keeps its Maxwell stresses in next.
template <typename T, typename In, typename Out>
void isotropic_part(const double* part, const PartFactors<T>& f, const MaxwellStep& m,
                    const StepStrains<T>& k, const In& state, Out& next, T* s) {
  const T elastic = f.h1 * f.g1 * 2.0;
  const T viscous = f.h2 * f.g2 * (2.0 * part[kViscous]);
  for (int i = 0; i < 6; ++i)
    s[i] = elastic * (part[kMean] * k.e[i] + part[kDynamic] * k.e_osc[i]);
  for (int n = 0; n < 5; ++n) {
    for (int i = 0; i < 6; ++i) {
      const T sn = m.decay[n] * state.viscous_I[n][i] + m.gain[n] * viscous * (k.e[i] - k.e_n[i]);
      s[i] += sn;
      next.viscous_I[n][i] = scalar_part(sn);
    }
  }
}

// A1: uniaxial along the fibres (4.51, 4.56, 4.62–4.69), spread onto s as (−½, −½, 1).
template <typename T, typename In, typename Out>
void fibre_uniaxial_part(const double* part, const PartFactors<T>& f, const MaxwellStep& m,
                         const StepStrains<T>& k, const In& state, Out& next, T* s) {
  const T viscous = f.h2 * f.g2 * (2.0 * part[kViscous]);
  T s3 = f.h1 * f.g1 * 2.0 * (part[kMean] * k.e[2] + part[kDynamic] * k.e_osc[2]);
  for (int n = 0; n < 5; ++n) {
    const T sn = m.decay[n] * state.viscous_A1[n] + m.gain[n] * viscous * (k.e[2] - k.e_n[2]);
    s3 += sn;
    next.viscous_A1[n] = scalar_part(sn);
  }
  s[0] -= 0.5 * s3;
  s[1] -= 0.5 * s3;
  s[2] += s3;
}

// A2: shear along the fibres, 23 and 13 (4.53–4.54, 4.58–4.59, 4.70–4.76); s = C'44 γ.
template <typename T, typename In, typename Out>
void fibre_shear_part(const double* part, const PartFactors<T>& f, const MaxwellStep& m,
                      const StepStrains<T>& k, const In& state, Out& next, T* s) {
  const T viscous = f.h2 * f.g2 * (2.0 * part[kViscous]);
  for (int c = 0; c < 2; ++c) {
    const int i = 3 + c;  // Voigt 23, 13
    T sc = f.h1 * f.g1 * 2.0 * (part[kMean] * k.e[i] + part[kDynamic] * k.e_osc[i]);
    for (int n = 0; n < 5; ++n) {
      const T sn =
          m.decay[n] * state.viscous_A2[n][c] + m.gain[n] * viscous * (k.e[i] - k.e_n[i]);
      sc += sn;
      next.viscous_A2[n][c] = scalar_part(sn);
    }
    s[i] += sc;
  }
}

// ∂s/∂e of one deviatoric part over a step whose damage driver the strain does not move (so h and
// g are constants): the elastic term's mean and dynamic moduli, e^o moving with e by osc_slope, and
// the five Maxwell elements' step gains, as the three parts above differentiate them.
template <typename T>
double part_step_modulus(const double* part, const PartFactors<T>& f, const MaxwellStep& m, double osc_slope) {
  double gains = 0.0;
  for (double g : m.gain) gains += g;
  return scalar_part(f.h1 * f.g1) * 2.0 * (part[kMean] + part[kDynamic] * osc_slope) +
         scalar_part(f.h2 * f.g2) * (2.0 * part[kViscous]) * gains;
}

// The rest of state_{n+1}: time, strain, ∫e and the damage drivers of the parts in use.
template <typename T, typename Out>
void record_step(const T* strain, const T* integral, const T* amplitude, const T* osc, int parts,
                 double t_next, Out& next) {
  next.time_s = t_next;
  for (int i = 0; i < 6; ++i) {
    next.strain[i] = scalar_part(strain[i]);
    next.dev_strain_integral[i] = scalar_part(integral[i]);
  }
  for (int j = 0; j < 3; ++j) {
    next.driver_amplitude[j] = j < parts ? scalar_part(amplitude[j]) : 0.0;
    next.driver_oscillating[j] = j < parts ? scalar_part(osc[j]) : 0.0;
  }
}

}  // namespace

std::array<double, 3> steady_drivers(const Vector6& strain_amplitude) {
  double e[6];
  std::array<double, 3> d{};
  deviatoric(strain_amplitude.data(), e);
  oscillation_norms(e, d.data());
  return d;
}

MaterialState::MaterialState() {
  for (auto& v : viscous_I) v.setZero();
  for (auto& v : viscous_A2) v.setZero();
  viscous_A1.fill(0.0);
}

MaterialPoint::MaterialPoint(std::vector<double> parameters, bool anisotropic, double reference_C,
                             Scheme scheme, DamageUpdate damage_update)
    : p_(std::move(parameters)), anisotropic_(anisotropic), reference_C_(reference_C),
      scheme_(scheme), damage_update_(damage_update) {
  const size_t expected = anisotropic ? kAnisotropicCount : kIsotropicCount;
  if (p_.size() != expected)
    throw core::UsageError("fritzson material point: expected " + std::to_string(expected) +
                           " parameters, got " + std::to_string(p_.size()));
}

void MaterialPoint::hold_damage_beyond(const std::vector<double>& ceiling) {
  const std::size_t parts = anisotropic_ ? 3 : 1;
  if (!ceiling.empty() && ceiling.size() != parts)
    throw core::UsageError("fritzson material point: the damage hold needs " + std::to_string(parts) +
                           " driver(s), got " + std::to_string(ceiling.size()));
  for (double c : ceiling)
    if (!(c >= 0.0) || !std::isfinite(c))
      throw core::UsageError("fritzson material point: a damage driver's hold must be finite and >= 0, not " +
                             core::format_number(c));
  for (std::size_t j = 0; j < 3; ++j) driver_ceiling_[j] = j < ceiling.size() ? ceiling[j] : kNoCeiling;
}

template <typename T, typename In, typename Out>
void MaterialPoint::update_impl(const In& state, const T* strain, double dt,
                                double temperature_C, Out& next, T* stress, double* step_moduli) const {
  if (!(dt >= 0.0) || !std::isfinite(dt))
    throw core::UsageError("fritzson material point: the time step must be finite and ≥ 0");
  const double* p = p_.data();
  StepStrains<T> k;
  deviatoric(strain, k.e);
  deviatoric(state.strain.data(), k.e_n);
  const double t_next = state.time_s + dt;
  T integral[6];
  running_mean(state.dev_strain_integral, k, dt, t_next, scheme_, integral);

  T osc[3];
  oscillation_norms(k.e_osc, osc);
  // amplitude: e^a_{n+1}, recorded; driver: what this step's stress uses (e^a_{n+1}, or e^a_n
  // when lagged, so the stress is smooth in the strain: no switch, no |Δe^o|).
  T amplitude[3], driver[3];
  const int parts = anisotropic_ ? 3 : 1;
  const bool lagged = damage_update_ == DamageUpdate::lagged;
  for (int j = 0; j < parts; ++j) {
    amplitude[j] = evolve_damage_driver(state.driver_amplitude[j], state.driver_oscillating[j], osc[j],
                                        p[kCd]);
    driver[j] = lagged ? T(state.driver_amplitude[j]) : amplitude[j];
    if (scalar_part(driver[j]) > driver_ceiling_[j]) driver[j] = T(driver_ceiling_[j]);
  }

  // Volumetric part (4.39): σ_p = K tr ε.
  const T pressure = p[kK] * (strain[0] + strain[1] + strain[2]);
  auto factors = [&](const double* part, const T& driver) {
    return part_factors(part_as<T>(part).data(), driver, temperature_C, reference_C_);
  };
  // e^o = e − ∫e/t moves with e by osc_slope (running_mean's rule: ∫e gains dt·e, or ½dt·e).
  const double osc_slope = t_next > 0.0 ? 1.0 - (scheme_ == Scheme::exponential ? 0.5 : 1.0) * dt / t_next : 0.0;
  T s[6];
  constexpr int kOffsets[3] = {kPartI, kPartA1, kPartA2};
  for (int j = 0; j < parts; ++j) {
    const double* part = p + kOffsets[j];
    const PartFactors<T> f = factors(part, driver[j]);
    const MaxwellStep m = maxwell_step(part, dt, scheme_);
    if (j == 0) isotropic_part(part, f, m, k, state, next, s);
    else if (j == 1) fibre_uniaxial_part(part, f, m, k, state, next, s);
    else fibre_shear_part(part, f, m, k, state, next, s);
    if (step_moduli) step_moduli[j] = part_step_modulus(part, f, m, osc_slope);
  }

  for (int i = 0; i < 3; ++i) stress[i] = pressure + s[i];
  for (int i = 3; i < 6; ++i) stress[i] = s[i];
  record_step(strain, integral, amplitude, osc, parts, t_next, next);
}

template <typename In, typename Out>
Vector6 MaterialPoint::update_any(const In& state, const Vector6& strain, double dt_s,
                                  double temperature_C, Out& next, Matrix6* tangent) const {
  Vector6 stress;
  if (!tangent) {
    update_impl<double>(state, strain.data(), dt_s, temperature_C, next, stress.data());
    return stress;
  }
  Jet6 strain_jet[6], stress_jet[6];
  for (int i = 0; i < 6; ++i) strain_jet[i] = Jet6(strain[i], i);
  update_impl<Jet6>(state, strain_jet, dt_s, temperature_C, next, stress_jet);
  for (int i = 0; i < 6; ++i) {
    stress[i] = stress_jet[i].a;
    for (int j = 0; j < 6; ++j) (*tangent)(i, j) = stress_jet[i].v[j];
  }
  return stress;
}

bool MaterialPoint::fixed_driver_tangent(const double* state_n, const double* state_next, const double* step_moduli,
                                         Matrix6& tangent) const {
  const FlatState<const double> in(state_n), out(state_next);
  const int parts = anisotropic_ ? 3 : 1;
  if (damage_update_ != DamageUpdate::lagged)
    for (int j = 0; j < parts; ++j)
      if (out.driver_oscillating[j] > in.driver_amplitude[j] && !(out.driver_amplitude[j] > driver_ceiling_[j]))
        return false;  // e^a_{n+1} grows with the strain, below its hold
  // σ_i = K tr ε + a_I e_i (e = dev ε, e_12 = γ12/2); A1 spreads a_A1 e_3 as (−½, −½, 1); A2 acts on
  // γ23, γ13 only, outside the in-plane columns.
  const double K = p_[kK], a_I = step_moduli[0], a_A1 = anisotropic_ ? step_moduli[1] : 0.0;
  tangent.setZero();
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) tangent(i, j) = K + a_I * ((i == j ? 1.0 : 0.0) - 1.0 / 3.0);
    tangent(0, j) += a_A1 / 6.0;
    tangent(1, j) += a_A1 / 6.0;
    tangent(2, j) -= a_A1 / 3.0;
  }
  tangent(5, 5) = 0.5 * a_I;
  return true;
}

Vector6 update_flat_in_plane(const MaterialPoint& point, const double* state, const Vector6& strain, double dt_s,
                             double temperature_C, double* next, Matrix6& tangent) {
  // Where no damage driver moves with the strain the stress is affine in it: its value in double
  // and the tangent in closed form (the Jet's derivative, without the Jet's arithmetic).
  const FlatState<const double> in(state);
  FlatState<double> out(next);
  Vector6 stress;
  double step_moduli[3];
  point.update_impl<double>(in, strain.data(), dt_s, temperature_C, out, stress.data(), step_moduli);
  if (point.fixed_driver_tangent(state, next, step_moduli, tangent)) return stress;
  // Each derivative is its own lane of the Jet's arithmetic: columns 0, 1, 5 are update_flat's.
  using Jet4 = ceres::Jet<double, 4>;  // four lanes, the last unseeded: two SSE packets (three lanes vectorise not at all)
  constexpr int kSeeds[3] = {0, 1, 5};
  Jet4 strain_jet[6], stress_jet[6];
  for (int i = 0; i < 6; ++i) strain_jet[i] = Jet4(strain[i]);
  for (int k = 0; k < 3; ++k) strain_jet[kSeeds[k]].v[k] = 1.0;
  point.update_impl<Jet4>(in, strain_jet, dt_s, temperature_C, out, stress_jet);
  tangent.setZero();
  for (int i = 0; i < 6; ++i) {
    stress[i] = stress_jet[i].a;
    for (int k = 0; k < 3; ++k) tangent(i, kSeeds[k]) = stress_jet[i].v[k];
  }
  return stress;
}

Vector6 MaterialPoint::update(const MaterialState& state, const Vector6& strain, double dt_s,
                              double temperature_C, MaterialState& next, Matrix6* tangent) const {
  return update_any(state, strain, dt_s, temperature_C, next, tangent);
}

Vector6 MaterialPoint::update_flat(const double* state, const Vector6& strain, double dt_s,
                                   double temperature_C, double* next, Matrix6* tangent) const {
  const FlatState<const double> in(state);
  FlatState<double> out(next);
  return update_any(in, strain, dt_s, temperature_C, out, tangent);
}

Eigen::Matrix3d MaterialPoint::update_deformation(const MaterialState& state,
                                                  const Eigen::Matrix3d& F, double dt_s,
                                                  double temperature_C, MaterialState& next,
                                                  Vector6* stress_unrotated,
                                                  Matrix6* tangent) const {
  return log_strain_step(F, stress_unrotated, [&](const Vector6& strain) {
    return update(state, strain, dt_s, temperature_C, next, tangent);
  });
}

PointLoading loading_for(const TestCondition& c, bool anisotropic) {
  PointLoading l;
  l.mode = c.mode;
  if (c.mode == TestMode::bulk) return l;
  const std::string& o = c.orientation;
  int i = c.mode == TestMode::uniaxial ? 1 : 0, j = 1;  // isotropic defaults: 22 and 12
  if (!o.empty()) {
    if (o.size() != 2 || o[0] < '1' || o[0] > '3' || o[1] < '1' || o[1] > '3')
      throw core::UsageError("fritzson: orientation '" + o + "' is not 11, 22, 33, 12, 13 or 23");
    i = o[0] - '1';
    j = o[1] - '1';
  } else if (anisotropic) {
    throw core::UsageError("fritzson (transversely isotropic) needs the test orientation");
  }
  if (c.mode == TestMode::uniaxial) {
    if (i != j) throw core::UsageError("fritzson: uniaxial orientation must be 11, 22 or 33");
    l.component = i;
  } else {
    if (i == j) throw core::UsageError("fritzson: shear orientation must be 12, 13 or 23");
    l.component = (i + j == 3) ? 3 : (i + j == 2) ? 4 : 5;  // 23, 13, 12
  }
  return l;
}

namespace {

// Uniaxial step: lateral normal stresses zero by Newton on the two lateral strains, starting
// from the last ones (in `strain` on entry) plus the incompressible guess for the increment.
Vector6 uniaxial_step(const MaterialPoint& point, const MaterialState& state, int axis,
                      double value, double dt, double temperature_C, double time_s,
                      Vector6& strain, MaterialState& next) {
  const int lateral[2] = {(axis + 1) % 3, (axis + 2) % 3};
  const double increment = value - strain[axis];
  strain[axis] = value;
  for (int l : lateral) strain[l] -= 0.5 * increment;
  Matrix6 tangent;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Vector6 stress = point.update(state, strain, dt, temperature_C, next, &tangent);
    const Eigen::Vector2d residual(stress[lateral[0]], stress[lateral[1]]);
    const double scale = 1.0 + std::abs(stress[axis]);
    if (residual.cwiseAbs().maxCoeff() <= 1e-10 * scale) return stress;
    Eigen::Matrix2d J;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) J(a, b) = tangent(lateral[a], lateral[b]);
    const Eigen::Vector2d step = J.partialPivLu().solve(-residual);
    strain[lateral[0]] += step[0];
    strain[lateral[1]] += step[1];
  }
  throw core::NumericalError("fritzson: uniaxial lateral-stress iteration did not converge at t = " +
                             core::format_number(time_s) + " s");
}

// One step of the test to the prescribed `value`; `strain` carries the last strain in and the
// new one out. Returns the test's stress.
double test_step(const MaterialPoint& point, const PointLoading& loading,
                 const MaterialState& state, double value, double dt, double temperature_C,
                 double time_s, Vector6& strain, MaterialState& next) {
  const int axis = loading.component;
  if (loading.mode == TestMode::shear) {
    strain.setZero();
    strain[axis] = value;
    return point.update(state, strain, dt, temperature_C, next)[axis];
  }
  if (loading.mode == TestMode::bulk) {
    strain.setZero();
    strain.head<3>().setConstant(value / 3.0);
    return point.update(state, strain, dt, temperature_C, next).head<3>().mean();
  }
  return uniaxial_step(point, state, axis, value, dt, temperature_C, time_s, strain, next)[axis];
}

}  // namespace

DriveResult drive(const MaterialPoint& point, const PointLoading& loading,
                  const StrainHistory& history, double temperature_C) {
  check_strain_history(history);
  DriveResult out;
  MaterialState state, next;
  Vector6 strain = Vector6::Zero();
  for (size_t n = 0; n < history.time_s.size(); ++n) {
    const double dt = n == 0 ? 0.0 : history.time_s[n] - history.time_s[n - 1];
    const double test_stress = test_step(point, loading, state, history.strain[n], dt,
                                         temperature_C, history.time_s[n], strain, next);
    state = next;
    out.stress.push_back(test_stress);
    out.strain.push_back(strain);
    out.driver_amplitude.push_back(state.driver_amplitude);
  }
  return out;
}

DriveResult drive_test(const MaterialPoint& point, const TestCondition& c,
                       const StrainHistory& history) {
  return drive(point, loading_for(c, point.anisotropic()), history, c.temperature_C);
}

Moduli<double> cycle_moduli(const std::vector<double>& t, const std::vector<double>& strain,
                            const std::vector<double>& stress, double frequency_Hz) {
  const double period = 1.0 / frequency_Hz, omega = 2.0 * kPi * frequency_Hz;
  const double t_end = t.back(), t_start = t_end - period;
  std::complex<double> eps_hat(0.0), sig_hat(0.0);
  double eps_mean = 0.0, sig_mean = 0.0;
  for (size_t n = 1; n < t.size(); ++n) {
    if (t[n - 1] < t_start - 1e-12 * period) continue;
    const double h = 0.5 * (t[n] - t[n - 1]);
    const std::complex<double> w0 = std::exp(std::complex<double>(0.0, -omega * t[n - 1]));
    const std::complex<double> w1 = std::exp(std::complex<double>(0.0, -omega * t[n]));
    eps_hat += h * (strain[n - 1] * w0 + strain[n] * w1);
    sig_hat += h * (stress[n - 1] * w0 + stress[n] * w1);
    eps_mean += h * (strain[n - 1] + strain[n]);
    sig_mean += h * (stress[n - 1] + stress[n]);
  }
  const std::complex<double> modulus = sig_hat / eps_hat;
  return {modulus.real(), modulus.imag(), sig_mean / eps_mean};
}

StrainHistory cyclic_history(double amplitude, double mean_strain, double frequency_Hz,
                             int cycles, int steps_per_cycle) {
  StrainHistory h;
  const int n = cycles * steps_per_cycle;
  h.time_s.reserve(n + 1);
  h.strain.reserve(n + 1);
  for (int k = 0; k <= n; ++k) {
    const double phase = 2.0 * kPi * double(k) / steps_per_cycle;
    h.time_s.push_back(double(k) / steps_per_cycle / frequency_Hz);
    h.strain.push_back(mean_strain - amplitude * std::cos(phase));
  }
  return h;
}

}  // namespace fitlib::model::fritzson
