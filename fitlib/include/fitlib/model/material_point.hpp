#pragma once
// The material-point contract (docs/model.md §"Material point"): every model gives, from its
// parameters, a point that an FE code drives without knowing which model it is.
//
//   auto point = card.model()->material_point(card.values().data(), {});   // or card::material_point
//   std::vector<double> state = point->initial_state(), next(point->state_size());
//   Vector6 sigma = point->update(state.data(), strain, dt_s, T_C, next.data(), &tangent);
//   state.swap(next);                                      // once the global step has converged
//
// Axes: material axes (1 radial, 2 along the belt, 3 fibre / axial). Voigt order 11, 22, 33, 23,
// 13, 12; strain shears are engineering (γ_ij = 2ε_ij), stress shears are σ_ij, so the tangent
// C = dσ/dε is symmetric for every linear model and the virtual work is σ·ε.
//
// Kinematics (docs/model.md §"Finite strain"):
//   small strain  ε = sym ∇u, σ Cauchy, tangent dσ_{n+1}/dε_{n+1};
//   finite strain total logarithmic form (docs/model.md §"Finite strain"):
//                 F = R U, the point is updated with the strain ln U in the unrotated frame and
//                 returns the unrotated Kirchhoff stress τ_U (τ = R τ_U Rᵀ); the tangent is
//                 dτ_U/d(ln U), the same 6 × 6 matrix as the small-strain tangent at ε = ln U.
//                 A rigid rotation of F leaves τ_U and the state unchanged (objectivity).
//
// The state is a flat array of doubles (state_size() of them) so an FE code keeps all its
// integration points in one contiguous block; it holds the last converged total strain, so
// update() needs no other memory. update() is pure: it reads state_n, writes state_{n+1} to a
// separate array, and may be called any number of times per step (Newton iterations).
#include <Eigen/Core>

#include <array>
#include <complex>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fitlib/core/fidelity.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using ComplexMatrix6 = Eigen::Matrix<std::complex<double>, 6, 6>;

// How a card becomes a point.
struct PointOptions {
  // The life's levels (core::Fidelity): complete — the model's own time-domain update (every
  //   model; `fitcli material-point --fidelity viscoelastic`); elastic — the elastic equivalent at
  //   `frequency_Hz` and `temperature_C`, the real part of the small-amplitude complex stiffness
  //   (storage moduli). beam has no material point (make_material_point refuses it).
  core::Fidelity fidelity = core::Fidelity::complete;
  double frequency_Hz = 1.0;                                          // elastic fidelity only
  double temperature_C = std::numeric_limits<double>::quiet_NaN();    // NaN = card reference
  // Elastic fidelity: the amplitude ε̂ of a steady strain oscillation about its mean, ε(t) = ε_mean +
  // ε̂ cos ωt (Voigt, engineering shear, with signs), at which the elastic equivalent is read. A
  // model whose moduli depend on the amplitude (Model::amplitude_dependent) gives the storage
  // stiffness of its steady response there, the secant of the cycle's first harmonic (Fritzson: the
  // damage drivers of that oscillation, held at damage_driver_hold when given; docs/model.md
  // "Elastic equivalent at an amplitude"); the others answer alike at every amplitude. Unset = the
  // small-amplitude (virgin) stiffness.
  std::optional<Vector6> strain_amplitude;
  // Bulk modulus K (MPa) for a linear shear card without its own K; NaN = the card's K (an error
  // when it has none).
  double bulk_modulus_MPa = std::numeric_limits<double>::quiet_NaN();
  // Fritzson only: the thesis's backward Euler (default) or the exponential scheme.
  bool fritzson_exponential = false;
  // Models with damage (ignored by the others): implicit — the damage variables of step n+1 follow
  //   from the strain of step n+1 and enter its stress and tangent (the model's own update);
  //   lagged — the stress of step n+1 uses the damage of the converged step n (explicit in damage,
  //   implicit in the viscoelastic part) and the damage is advanced from the step's strain for
  //   step n+2: an O(Δt) difference, and a stress smooth in the strain for an FE Newton iteration
  //   (docs/model.md §"Material point", docs/decisions.md "Lagged damage update").
  enum class DamageUpdate { implicit, lagged };
  DamageUpdate damage_update = DamageUpdate::implicit;
  // Models with damage (ignored by the others): the damage drivers, in the model's order
  // (Model::damage_drivers), beyond which the damage is held — what the tests behind the card reached
  // (fit.data_window.damage_driver), as a solver holds tabulated data constant outside its range;
  // empty = the damage law at every amplitude (docs/decisions.md "Complete level: damage held
  // beyond the tested amplitudes").
  std::vector<double> damage_driver_hold;
};

class MaterialPoint {
 public:
  virtual ~MaterialPoint() = default;

  // A short description for messages and restart files ("prony 3-D, 4 terms", ...).
  virtual std::string describe() const = 0;

  // Number of doubles in the state, and the state of the virgin material at rest.
  virtual std::size_t state_size() const = 0;
  virtual std::vector<double> initial_state() const = 0;

  // Small strain: one increment to the total strain ε_{n+1} over dt ≥ 0 s at temperature T (°C;
  // NaN = reference). Returns σ_{n+1}; writes state_{n+1} (state_size() doubles, may not alias
  // state_n) and, when asked, the consistent tangent dσ_{n+1}/dε_{n+1} of this very update.
  // Throws core::UsageError for dt < 0, core::NumericalError when the update has no result.
  virtual Vector6 update(const double* state_n, const Vector6& strain, double dt_s,
                         double temperature_C, double* state_next,
                         Matrix6* tangent = nullptr) const = 0;

  // Steady small-amplitude response at frequency f and temperature T about the virgin state:
  // σ̂ = C*(ω) ε̂ (storage + i·loss). The elastic equivalent is its real part.
  virtual ComplexMatrix6 complex_stiffness(double frequency_Hz, double temperature_C) const = 0;

  // Whether the finite-strain response in plane strain (the 1–2 plane, F e3 = e3: update_plane_strain,
  // the segment FE) is hyperelastic, so the in-plane tangent dP/dF is major-symmetric and an FE code
  // may factor with LDLᵀ: true for an elastic point whose stiffness is isotropic in the 1–2 plane
  // (isotropic, or transversely isotropic about axis 3 as Fritzson's cord-direction parts), so
  // the in-plane τ_U = C ln U is coaxial with U (Hencky energy). A rate-dependent, damaging or
  // in-plane anisotropic point (τ_U need not be conjugate to ln U) says false.
  virtual bool symmetric_tangent() const { return false; }

  // Finite strain, total logarithmic form (see the top of this file). Returns the Kirchhoff
  // stress τ in the current frame (3 × 3); optional: τ_U (Voigt) and dτ_U/d(ln U).
  Eigen::Matrix3d update_deformation(const double* state_n, const Eigen::Matrix3d& F, double dt_s,
                                     double temperature_C, double* state_next,
                                     Vector6* stress_unrotated = nullptr,
                                     Matrix6* tangent = nullptr) const;

  // Plane strain in the 1–2 plane (ε33 = γ23 = γ13 = 0; belt-mechanics §5): in-plane strain
  // (ε11, ε22, γ12) → (σ11, σ22, σ12), the out-of-plane σ33 and the 3 × 3 in-plane tangent.
  struct PlaneStrainResult {
    Eigen::Vector3d stress;
    double stress_33 = 0.0;
    Eigen::Matrix3d tangent;
  };
  PlaneStrainResult update_plane_strain(const double* state_n, const Eigen::Vector3d& strain,
                                        double dt_s, double temperature_C, double* state_next,
                                        bool want_tangent = true) const;

  // Restart files: {"point": describe(), "state": [...]} and back. from_json checks the size.
  nlohmann::json state_to_json(const double* state) const;
  std::vector<double> state_from_json(const nlohmann::json& j) const;
};

using MaterialPointPtr = std::shared_ptr<const MaterialPoint>;

// Checks of a point's conditions where they come from a user (not in update, the FE code's hot
// path): core::UsageError "WHO: the temperature must be finite (NaN = the card's reference)", and
// for a steady response also "WHO: the frequency must be finite and > 0 Hz".
void require_temperature(const std::string& who, double temperature_C);
void require_steady_condition(const std::string& who, double frequency_Hz, double temperature_C);

// card → point in one call: `model.material_point(values, options)` (model.hpp); this is the same
// with a values vector whose size is checked.
MaterialPointPtr make_material_point(const Model& model, const std::vector<double>& values,
                                     const PointOptions& options = {});

// The isotropic linear viscoelastic point (docs/model.md §"Linear viscoelastic point") of a shear
// model that is an exact Maxwell or Kelvin series (Model::maxwell_series, kelvin_series), with
// K from options or Model::bulk_modulus and the model's temperature_factors: what a new linear
// model returns from material_point (docs/model.md §"How a new model plugs in").
MaterialPointPtr series_point(std::shared_ptr<const Model> model, std::vector<double> values,
                              const PointOptions& options);

// ln U (Voigt, engineering shear) and the rotation R of F = R U; NumericalError when det F ≤ 0.
Vector6 log_strain(const Eigen::Matrix3d& F, Eigen::Matrix3d* rotation = nullptr);
// R S Rᵀ of a Voigt stress S (the unrotated Kirchhoff stress to the current frame).
Eigen::Matrix3d rotate_stress(const Vector6& stress, const Eigen::Matrix3d& rotation);
// The total log-strain step every point shares: ε = ln U of F, `update(ε)` → τ_U, τ = R τ_U Rᵀ.
template <typename Update>
Eigen::Matrix3d log_strain_step(const Eigen::Matrix3d& F, Vector6* stress_unrotated, Update&& update) {
  Eigen::Matrix3d R;
  const Vector6 s = update(log_strain(F, &R));
  if (stress_unrotated) *stress_unrotated = s;
  return rotate_stress(s, R);
}

// ---- drive(): one driver for every point, as MTest does -------------------------------------
// Each of the six Voigt components is either strain-controlled or stress-controlled, with its
// value at each time (empty values = 0 at every time). Stress-controlled components are solved
// by Newton with the point's consistent tangent. time_s[0] is the start (the material is at rest
// before it; nonzero first values are applied as a jump).
struct DriveControl {
  enum class Imposed { strain, stress };
  Imposed imposed = Imposed::stress;  // default: a free (traction-free) component
  std::vector<double> values;         // one per time, or empty (= 0)
};

struct DriveProgram {
  std::vector<double> time_s;
  std::array<DriveControl, 6> components;
  std::vector<double> temperature_C;  // one per time, or empty (= the card's reference)
  double stress_tolerance_MPa = 1e-10;  // relative to 1 + |σ|
  int max_iterations = 30;
};

struct DriveResult {
  std::vector<double> time_s;
  std::vector<Vector6> strain;  // all components, stress-controlled ones solved
  std::vector<Vector6> stress;
  std::vector<double> final_state;
};

// Throws core::UsageError for a malformed program, core::NumericalError when Newton fails.
DriveResult drive(const MaterialPoint& point, const DriveProgram& program);

// Programs of the dynamic tests: shear (γ_ij imposed, all other strains zero), uniaxial (ε_ii
// imposed, the other two normal stresses zero, shears zero), bulk (ε = θ/3 (1, 1, 1)); the Voigt
// component follows the test's orientation label (isotropic default: 12 / 22).
DriveProgram test_program(const TestCondition& condition, const StrainHistory& history);
// The test's scalar stress from a drive result (σ of the imposed component; bulk: mean stress).
std::vector<double> test_stress(const DriveResult& result, const TestCondition& condition);

}  // namespace fitlib::model
