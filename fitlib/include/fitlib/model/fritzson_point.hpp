#pragma once
// Time-domain integration of Fritzson's model at one material point (thesis Report II §7.1,
// docs/fritzson.md §4), in the form a segment solver calls per
// integration point: a pure update(state_n, strain_{n+1}, dt, T) → stress, consistent tangent
// and state_{n+1}. Strain and stress are in material axes (1 radial, 2 along the belt, 3 fibre).
//
// Voigt order (docs/model.md, "Material point"): 11, 22, 33, 23, 13, 12; strain shears are engineering (γ = 2ε_ij).
// Small-strain variant: the strain is ε. Logarithmic (total) variant: the strain is
// ln U = ½ ln(FᵀF) (docs/model.md, "Finite strain"), the stress is the Kirchhoff stress in the unrotated frame.
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <limits>
#include <type_traits>
#include <string>
#include <vector>

#include "fitlib/model/fritzson.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model::fritzson {

using model::Matrix6;
using model::Vector6;
using model::log_strain;  // ln U and R of F = R U (material_point.hpp)

// backward_euler: the thesis's scheme (docs/fritzson.md §4), first order: Maxwell s_{n+1} =
//   τ/(τ+Δt)(s_n + 2G h2 g2 Δe), running mean by the rectangle rule.
// exponential: exact for piecewise-linear strain (Maxwell s_{n+1} = e^{−Δt/τ}s_n +
//   2G h2 g2 τ(1 − e^{−Δt/τ})/Δt·Δe, running mean by the trapezoid rule), second order.
// Damage evolution is backward Euler in both.
enum class Scheme { backward_euler, exponential };

// implicit: the step's stress uses e^a_{n+1} (4.37 within the step, the thesis's update);
// lagged: it uses the converged e^a_n, and e^a_{n+1} is recorded for the next step
// (model::PointOptions::DamageUpdate; docs/fritzson.md §4).
using DamageUpdate = model::PointOptions::DamageUpdate;

// Backward-Euler damage evolution (4.37, with the dot the print lacks): ė_a = C_d(1 − e_a/e_o)|ė_o|
// while e_o > e_a, else 0. Implicit in e_a: e_a' = (e_a + C_d|Δe_o|)/(1 + C_d|Δe_o|/e_o), which
// lies in [e_a, e_o] for every C_d (stable and never overshoots the driver).
template <typename T>
T evolve_damage_driver(double amplitude_n, double oscillating_n, const T& oscillating, double c_d) {
  if (!(scalar_part(oscillating) > amplitude_n)) return T(amplitude_n);
  T increment = oscillating - oscillating_n;
  if (scalar_part(increment) < 0.0) increment = -increment;
  return (amplitude_n + c_d * increment) / (T(1.0) + c_d * increment / oscillating);
}

// Solution-dependent variables; the caller keeps the converged one per integration point.
struct MaterialState {
  double time_s = 0.0;                        // time since the running mean started
  Vector6 strain = Vector6::Zero();           // total strain ε_n (Voigt, engineering shear)
  Vector6 dev_strain_integral = Vector6::Zero();  // ∫₀ᵗ e dτ, deviatoric, tensor shear comps
  // Damage: driver amplitude e^a (4.37) and last oscillating driver e^o, for I, A1, A2.
  std::array<double, 3> driver_amplitude{{0.0, 0.0, 0.0}};
  std::array<double, 3> driver_oscillating{{0.0, 0.0, 0.0}};
  // Maxwell stresses of the five elements: isotropic deviatoric (Voigt, tensor comps), A1 (s3),
  // A2 (s23, s13).
  std::array<Vector6, 5> viscous_I{};
  std::array<double, 5> viscous_A1{};
  std::array<Eigen::Vector2d, 5> viscous_A2{};
  MaterialState();
};

// A MaterialState in a flat array of kFlatStateSize doubles (the contract's state,
// material_point.hpp), with the same member syntax over borrowed storage, so one update serves
// both without copies. Order: time, strain (6), ∫e (6), e^a (3), e^o (3), viscous I (5 × 6),
// A1 (5), A2 (5 × 2). D is double or const double.
constexpr std::size_t kFlatStateSize = 64;
template <typename D>
struct FlatState {
  using Vec = std::conditional_t<std::is_const_v<D>, Eigen::Map<const Vector6>, Eigen::Map<Vector6>>;
  struct Rows {
    D* p;
    int width;
    D* operator[](int n) const { return p + width * n; }
  };
  explicit FlatState(D* x)
      : time_s(x[0]), strain(x + 1), dev_strain_integral(x + 7), driver_amplitude(x + 13),
        driver_oscillating(x + 16), viscous_I{x + 19, 6}, viscous_A1(x + 49), viscous_A2{x + 54, 2} {}
  D& time_s;
  Vec strain, dev_strain_integral;
  D* driver_amplitude;
  D* driver_oscillating;
  Rows viscous_I;
  D* viscous_A1;
  Rows viscous_A2;
};

class MaterialPoint {
 public:
  // parameters: 14 (isotropic) or 38 (anisotropic) in the order of fritzson.hpp.
  MaterialPoint(std::vector<double> parameters, bool anisotropic, double reference_C,
                Scheme scheme = Scheme::backward_euler,
                DamageUpdate damage_update = DamageUpdate::implicit);

  // One increment to strain_{n+1} over dt ≥ 0 at temperature T (°C; NaN = reference). Writes
  // state_{n+1} to `next` (state is untouched, so Newton iterations may call it repeatedly) and,
  // when asked, the consistent tangent dσ_{n+1}/dε_{n+1} (exact derivative of this update,
  // computed by forward-mode automatic differentiation).
  Vector6 update(const MaterialState& state, const Vector6& strain, double dt_s,
                 double temperature_C, MaterialState& next, Matrix6* tangent = nullptr) const;

  // Logarithmic (total) variant: F in material axes → ln U, update, Kirchhoff stress. Returns
  // the Kirchhoff stress in the current (rotated) frame τ = R σ_U Rᵀ; `stress_unrotated` and
  // `tangent` (dσ_U/d ln U) are optional.
  Eigen::Matrix3d update_deformation(const MaterialState& state, const Eigen::Matrix3d& F,
                                     double dt_s, double temperature_C, MaterialState& next,
                                     Vector6* stress_unrotated = nullptr,
                                     Matrix6* tangent = nullptr) const;

  // The same update on a flat state (FlatState layout); bit-identical to update().
  Vector6 update_flat(const double* state, const Vector6& strain, double dt_s,
                      double temperature_C, double* next, Matrix6* tangent = nullptr) const;

  bool anisotropic() const { return anisotropic_; }
  Scheme scheme() const { return scheme_; }
  DamageUpdate damage_update() const { return damage_update_; }
  const std::vector<double>& parameters() const { return p_; }
  // Hold the damage drivers (I, or I, A1, A2) at `ceiling` (PointOptions::damage_driver_hold): the
  // stress reads min(e^a, ceiling), the state records e^a itself; empty = no hold.
  void hold_damage_beyond(const std::vector<double>& ceiling);
  bool damage_held() const { return driver_ceiling_[0] != kNoCeiling; }
  // The driver the stress reads for an amplitude e^a of part j (0 I, 1 A1, 2 A2): e^a, or its hold.
  double held_driver(int j, double amplitude) const { return std::min(amplitude, driver_ceiling_[j]); }

  // The tangent's in-plane columns (0, 1, 5) of the step state_n → state_next (FlatState layout, as
  // update_impl wrote it with its step_moduli) in closed form, when no damage driver moves with the
  // strain (lagged, not growing, or beyond its hold): then the stress is affine in the strain. False
  // otherwise.
  bool fixed_driver_tangent(const double* state_n, const double* state_next, const double* step_moduli,
                            Matrix6& tangent) const;

  // The update in any scalar type T (double, or a Jet for the tangent) on any state type.
  // `step_moduli` (optional, one per part): ∂s/∂e of each part at its step's damage factors, the
  // tangent where no driver moves (fixed_driver_tangent).
  template <typename T, typename In, typename Out>
  void update_impl(const In& state, const T* strain, double dt_s, double temperature_C,
                   Out& next, T* stress, double* step_moduli = nullptr) const;

 private:
  template <typename In, typename Out>
  Vector6 update_any(const In& state, const Vector6& strain, double dt_s, double temperature_C,
                     Out& next, Matrix6* tangent) const;

  std::vector<double> p_;
  bool anisotropic_;
  double reference_C_;
  Scheme scheme_;
  DamageUpdate damage_update_;
  static constexpr double kNoCeiling = std::numeric_limits<double>::infinity();
  std::array<double, 3> driver_ceiling_{{kNoCeiling, kNoCeiling, kNoCeiling}};
};

// The damage drivers (I, A1, A2: 4.32, 4.77, 4.78) of a steady oscillation of amplitude ε̂ (Voigt,
// engineering shear) about its mean: the norms of its deviatoric part, the e^a the update reaches
// once the amplitude has saturated (the elastic equivalent at an amplitude, PointOptions::strain_amplitude).
std::array<double, 3> steady_drivers(const Vector6& strain_amplitude);

// A dynamic test's loading at one point: which strain the test prescribes and which stresses
// are zero. shear: γ_ij prescribed, all other strains 0 (simple shear, γ < 0.1, docs/fritzson.md §7);
// uniaxial: ε_ii prescribed, the other normal stresses zero (lateral strains solved by Newton
// with the consistent tangent), shears 0; bulk: ε = θ/3·(1,1,1), the stress returned is the mean
// normal stress.
struct PointLoading {
  TestMode mode = TestMode::shear;
  int component = 5;  // Voigt index of the prescribed strain (0–2 uniaxial, 3–5 shear)
};
PointLoading loading_for(const TestCondition& c, bool anisotropic);

struct DriveResult {
  std::vector<double> stress;             // the test's stress (MPa) at each sample
  std::vector<Vector6> strain;            // full strain at each sample (lateral strains solved)
  std::vector<std::array<double, 3>> driver_amplitude;  // e^a of I, A1, A2 at each sample
};

// Drives the point through a scalar strain history (t_s[0] is the start; the material is at rest
// before it, and a nonzero first strain is applied as a jump). Throws NumericalError when the
// lateral-stress Newton iteration does not converge.
DriveResult drive(const MaterialPoint& point, const PointLoading& loading,
                  const StrainHistory& history, double temperature_C);
DriveResult drive_test(const MaterialPoint& point, const TestCondition& c,
                       const StrainHistory& history);

// Moduli of one steady cycle, by projection on the fundamental over [t_end − 1/f, t_end]
// (trapezoid rule): storage + i·loss = σ̂/ε̂, mean = mean stress / mean strain.
Moduli<double> cycle_moduli(const std::vector<double>& time_s, const std::vector<double>& strain,
                            const std::vector<double>& stress, double frequency_Hz);

// Cyclic strain of Report II §7.2 and Report V: ε(t) = mean − a cos(2πft), which starts at
// mean − a (0 when mean = a), sampled with `steps_per_cycle` over `cycles`.
StrainHistory cyclic_history(double amplitude, double mean_strain, double frequency_Hz,
                             int cycles, int steps_per_cycle);

}  // namespace fitlib::model::fritzson
