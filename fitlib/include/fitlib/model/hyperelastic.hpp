#pragma once
// Isotropic hyperelastic laws (docs/hyperelastic.md): the strain energy W of the isochoric
// stretches plus a volumetric U(J), in the Abaqus forms
//   neo-hooke           C10 (Ī1 − 3)
//   mooney-rivlin       C10 (Ī1 − 3) + C01 (Ī2 − 3) [+ C11 (Ī1 − 3)(Ī2 − 3)]   terms 2 | 3
//   yeoh                Σ_{i=1..3} Ci0 (Ī1 − 3)^i
//   reduced-polynomial  Σ_{i=1..N} Ci0 (Ī1 − 3)^i                              terms N ≤ 6
//   ogden               Σ 2 μ_i/α_i² (λ̄1^α_i + λ̄2^α_i + λ̄3^α_i − 3)             terms N ≤ 6
//   arruda-boyce        μ Σ_{k=1..5} c_k/λ_m^(2k−2) (Ī1^k − 3^k), c = 1/2, 1/20, 11/1050, 19/7000, 519/673750
//   gent                −μ J_m/2 ln(1 − (Ī1 − 3)/J_m)
// U(J) = (J − 1)²/D1 (arruda-boyce: (1/D1)((J² − 1)/2 − ln J)); incompressible by default, option
// "compressible": true adds D1 (1/MPa, K0 = 2/D1). Test modes of a compressible law other than
// volumetric are evaluated incompressible (docs/decisions.md "Hyperelastic: deviatoric and
// volumetric fitted apart").
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/model/deformation_mode.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model {

// The law as typed data for exports (no name lookups outside model).
enum class HyperelasticFamily { neo_hooke, mooney_rivlin, yeoh, reduced_polynomial, ogden, arruda_boyce, gent };

struct HyperelasticForm {
  HyperelasticFamily family = HyperelasticFamily::neo_hooke;
  // Polynomial families: C_ij of (Ī1 − 3)^i (Ī2 − 3)^j, MPa.
  struct Coefficient {
    int i = 1, j = 0;
    double value_MPa = 0.0;
  };
  std::vector<Coefficient> coefficients;
  int order = 1;  // N of the polynomial (largest i + j) or the Ogden terms
  // Ogden, Abaqus convention (μ0 = Σ μ_i).
  std::vector<double> mu_MPa, alpha;
  // Arruda–Boyce: mu_MPa[0], locking stretch λ_m; Gent: mu_MPa[0], J_m.
  double lambda_m = 0.0, J_m = 0.0;
  double D1_per_MPa = 0.0;  // 0: incompressible
  double initial_shear_modulus_MPa = 0.0;
};

class HyperelasticLaw {
 public:
  virtual ~HyperelasticLaw() = default;
  virtual bool compressible() const = 0;
  // Nominal stress of `mode` (MPa; model/deformation_mode.hpp) at abscissa x (stretch, shear
  // strain or volume ratio); with `gradient`, dP/dp (size() values).
  virtual double nominal_stress(const double* p, DeformationMode mode, double x, double* gradient = nullptr) const = 0;
  // Cauchy stress of the same component (σ11 = P λ; σ12 = P12; the pressure unchanged).
  double cauchy_stress(const double* p, DeformationMode mode, double x) const;
  // W (MPa) at the principal stretches (isochoric part of λ̄_i = J^−1/3 λ_i, plus U(J) when compressible).
  virtual double energy(const double* p, const std::array<double, 3>& stretches) const = 0;
  // Principal Kirchhoff stresses τ_i = λ_i ∂W/∂λ_i (compressible; incompressible: the deviatoric
  // part plus `pressure_MPa`·J, for a point with a given bulk modulus, see material_point).
  virtual std::array<double, 3> principal_kirchhoff(const double* p, const std::array<double, 3>& stretches,
                                                    double bulk_modulus_MPa) const = 0;
  // Hessian of W(ε1, ε2) in the principal log strains of an incompressible state (ε3 = −ε1 − ε2,
  // σ3 = 0) at (λ1, λ2): Drucker stability needs it positive definite (docs/hyperelastic.md §"Stability").
  virtual std::array<double, 3> drucker_tangent(const double* p, double lambda1, double lambda2) const = 0;
  virtual double initial_shear_modulus(const double* p) const = 0;
  virtual HyperelasticForm form(const double* p) const = 0;
  // The stretch range where the law is defined (Gent: below locking), "" inside it.
  virtual std::string outside_domain(const double* p, DeformationMode mode, double x) const { return {}; }
};

bool is_hyperelastic_kind(const std::string& kind);
ModelPtr make_hyperelastic_model(const std::string& kind, const nlohmann::json& options);
// The hyperelastic kinds, in the order help texts list them.
const std::vector<std::string>& hyperelastic_kinds();

// The visco-hyperelastic card (docs/hyperelastic.md §"Visco-hyperelastic"): options
// {"base": a hyperelastic kind, "base_options": {...}, "terms": N}; parameters: the base's
// (its long-term response), then g_1..g_N (relative shear moduli, Σ g_i < 1) and tau_1..tau_N (s).
bool is_visco_hyperelastic_kind(const std::string& kind);
ModelPtr make_visco_hyperelastic_model(const nlohmann::json& options);

// Drucker stability along one mode (uniaxial, equibiaxial or planar) from stretch 1 outward to
// `stretch` (> 1 tension, < 1 compression): the first stretch on a log-spaced scan where the
// tangent is not positive definite (or the law leaves its domain), 0 when stable all the way.
double first_unstable_stretch(const HyperelasticLaw& law, const double* p, DeformationMode mode, double stretch,
                              int steps = 400);

}  // namespace fitlib::model
