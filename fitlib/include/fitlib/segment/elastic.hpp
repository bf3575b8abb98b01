#pragma once
// The law at an integration point of the plane-strain segment: first Piola–Kirchhoff stress and
// its consistent tangent dP/dF from an in-plane deformation gradient (F33 = 1), with a flat state
// per point (the solver keeps all points' states in one block and commits them when a step has
// converged). The materials of the belt come from cards through the material-point contract
// (point_law.hpp); two segment-private hyperelastic laws stay here: St Venant–Kirchhoff, the law
// CalculiX's *ELASTIC is under NLGEOM (the oracle comparison; docs/decisions.md), and a
// compressible neo-Hookean law.
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace fitlib::segment {

using Matrix2 = Eigen::Matrix2d;
using Tangent = Eigen::Matrix4d;  // A(2i+J, 2k+L) = ∂P_iJ/∂F_kL

struct PointResponse {
  Matrix2 P;             // first Piola–Kirchhoff stress, MPa
  Tangent A = Tangent::Zero();  // ∂P/∂F, MPa (zero when the step asked for no tangent)
  double sigma33_MPa = 0.0;  // out-of-plane Cauchy stress (plane-strain constraint)
};

struct PointStep {                      // one update of one integration point
  const double* state_n = nullptr;     // state_size() doubles, last converged
  double* state_next = nullptr;        // state_size() doubles, written
  double dt_s = 0.0;
  double temperature_C = std::numeric_limits<double>::quiet_NaN();  // NaN = the card's reference
  bool tangent = true;                 // false: a residual-only pass; A may be left zero
};

class PlaneStrainLaw {
 public:
  virtual ~PlaneStrainLaw() = default;
  virtual std::size_t state_size() const { return 0; }
  virtual std::vector<double> initial_state() const { return {}; }
  // Whether dP/dF is major-symmetric (a hyperelastic law): the solver may then use LDLᵀ.
  virtual bool symmetric_tangent() const { return true; }
  // A non-finite P or A (or a thrown core::NumericalError) marks the point as failed.
  virtual PointResponse respond(const Matrix2& F, const PointStep& step) const = 0;
  // From the virgin state over dt = 0 at the reference temperature.
  PointResponse respond(const Matrix2& F) const;
};

// hencky: the contract's `elastic-iso` point (τ_U = λ tr(ln U) I + 2μ ln U) through ContractLaw.
enum class ElasticLaw { st_venant_kirchhoff, neo_hookean, hencky };
ElasticLaw elastic_law_from_string(const std::string& name);  // "stvk" | "neo-hookean" | "hencky"
std::string to_string(ElasticLaw law);

std::unique_ptr<PlaneStrainLaw> make_elastic(ElasticLaw law, double E_MPa, double nu);

}  // namespace fitlib::segment
