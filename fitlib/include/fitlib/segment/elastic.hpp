#pragma once
// Isotropic elastic laws for the plane-strain segment, written against a small interface
// (first Piola–Kirchhoff stress and its consistent tangent dP/dF from an in-plane deformation
// gradient, F33 = 1) so the material-point contract of `model` can replace them by an adapter.
// St Venant–Kirchhoff is the law CalculiX's *ELASTIC uses under NLGEOM (the oracle comparison);
// the compressible neo-Hookean law is the default for large strains (it resists inversion).
#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/LU>

namespace fitlib::segment {

using Matrix2 = Eigen::Matrix2d;
using Tangent = Eigen::Matrix4d;  // A(2i+J, 2k+L) = ∂P_iJ/∂F_kL

struct PointResponse {
  Matrix2 P;             // first Piola–Kirchhoff stress, MPa
  Tangent A;             // ∂P/∂F, MPa
  double sigma33_MPa = 0.0;  // out-of-plane Cauchy stress (plane-strain constraint)
};

class PlaneStrainLaw {
 public:
  virtual ~PlaneStrainLaw() = default;
  virtual PointResponse respond(const Matrix2& F) const = 0;
};

enum class ElasticLaw { st_venant_kirchhoff, neo_hookean };
ElasticLaw elastic_law_from_string(const std::string& name);  // "stvk" | "neo-hookean"
std::string to_string(ElasticLaw law);

std::unique_ptr<PlaneStrainLaw> make_elastic(ElasticLaw law, double E_MPa, double nu);

}  // namespace fitlib::segment
