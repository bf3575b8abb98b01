// The material point of a hyperelastic card (docs/hyperelastic.md §"Material point"): the total
// log-strain contract of material_point.hpp with τ_U = Σ τ_i n_i ⊗ n_i, the principal Kirchhoff
// stresses of W at the principal stretches λ_i = exp(e_i) of ln U (isotropy makes τ_U coaxial
// with ln U). No state: the law is elastic.
#include <Eigen/Eigenvalues>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "points.hpp"

namespace fitlib::model {
namespace {

Eigen::Matrix3d tensor_of(const Vector6& v) {  // engineering shears → tensor
  Eigen::Matrix3d e;
  e << v[0], 0.5 * v[5], 0.5 * v[4], 0.5 * v[5], v[1], 0.5 * v[3], 0.5 * v[4], 0.5 * v[3], v[2];
  return e;
}

class HyperelasticPoint final : public MaterialPoint {
 public:
  HyperelasticPoint(std::shared_ptr<const Model> model, std::vector<double> values, double bulk_MPa)
      : model_(std::move(model)), law_(*model_->hyperelastic()), p_(std::move(values)), bulk_MPa_(bulk_MPa) {
    G_ = law_.initial_shear_modulus(p_.data());
    if (!(G_ > 0.0)) throw core::UsageError(model_->kind() + ": the initial shear modulus must be > 0 for a point");
    if (law_.compressible()) bulk_MPa_ = model_->bulk_modulus(p_.data());
  }
  std::string describe() const override {
    return model_->kind() + " hyperelastic, K " + core::format_number(bulk_MPa_) + " MPa";
  }
  std::size_t state_size() const override { return 0; }
  std::vector<double> initial_state() const override { return {}; }
  bool symmetric_tangent() const override { return true; }

  Vector6 update(const double*, const Vector6& strain, double dt_s, double, double*, Matrix6* tangent) const override {
    if (!(dt_s >= 0.0)) throw core::UsageError(describe() + ": the time step must be ≥ 0");
    const Vector6 s = stress(strain);
    if (tangent) {  // central differences: τ_U is smooth in ln U, also at repeated eigenvalues
      const double h = 1e-6;
      for (int k = 0; k < 6; ++k) {
        Vector6 a = strain, b = strain;
        a[k] += h, b[k] -= h;
        tangent->col(k) = (stress(a) - stress(b)) / (2.0 * h);
      }
    }
    return s;
  }

  ComplexMatrix6 complex_stiffness(double, double) const override {
    return points::isotropic_stiffness<std::complex<double>>(bulk_MPa_, G_);
  }

 private:
  Vector6 stress(const Vector6& strain) const {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(tensor_of(strain));
    const Eigen::Vector3d e = eig.eigenvalues();
    const auto t = law_.principal_kirchhoff(p_.data(), {std::exp(e[0]), std::exp(e[1]), std::exp(e[2])}, bulk_MPa_);
    const Eigen::Matrix3d& n = eig.eigenvectors();
    const Eigen::Matrix3d tau = n * Eigen::Vector3d(t[0], t[1], t[2]).asDiagonal() * n.transpose();
    Vector6 v;
    v << tau(0, 0), tau(1, 1), tau(2, 2), tau(1, 2), tau(0, 2), tau(0, 1);
    if (!v.allFinite()) throw core::NumericalError(describe() + ": the stress is not finite at this strain");
    return v;
  }

  std::shared_ptr<const Model> model_;
  const HyperelasticLaw& law_;
  std::vector<double> p_;
  double bulk_MPa_, G_ = 0.0;
};

}  // namespace

MaterialPointPtr hyperelastic_point(std::shared_ptr<const Model> model, std::vector<double> values,
                                    const PointOptions& options) {
  const HyperelasticLaw* law = model->hyperelastic();
  if (!law) throw core::UsageError(model->kind() + " is not hyperelastic");
  if (!law->compressible() && !(options.bulk_modulus_MPa > 0.0))
    throw core::UsageError(model->kind() + ": an incompressible card's point needs a bulk modulus "
                           "(PointOptions::bulk_modulus_MPa, or a compressible card with D1)");
  auto point = std::make_shared<HyperelasticPoint>(model, std::move(values), options.bulk_modulus_MPa);
  if (options.fidelity == core::Fidelity::elastic)
    return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
  return point;
}

}  // namespace fitlib::model
