// The linear elastic material point and the elastic equivalent of any point (docs/model.md
// §"Elastic fidelity").
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "points.hpp"

namespace fitlib::model::points {
namespace {

// In plane strain (ε33 = γ13 = γ23 = 0) the in-plane stress is λ' tr(ε) I + 2μ' ε when C11 = C22,
// C66 = (C11 − C12)/2 and the shear γ12 couples to no normal stress (and C is symmetric), to round-off.
bool isotropic_in_plane(const Matrix6& C) {
  const double tol = 1e-10 * C.cwiseAbs().maxCoeff();
  const double worst = std::max({std::abs(C(0, 0) - C(1, 1)), std::abs(C(5, 5) - 0.5 * (C(0, 0) - C(0, 1))),
                                 std::abs(C(0, 5)), std::abs(C(1, 5)), std::abs(C(2, 5)),
                                 (C - C.transpose()).cwiseAbs().maxCoeff()});
  return worst <= tol;
}

class ElasticPoint final : public MaterialPoint {
 public:
  ElasticPoint(const Matrix6& C, std::string description)
      : C_(C), description_(std::move(description)) {
    if (!C_.allFinite()) throw core::NumericalError(description_ + ": stiffness is not finite");
    isotropic_in_plane_ = isotropic_in_plane(C_);
  }
  std::string describe() const override { return description_; }
  std::size_t state_size() const override { return 0; }
  std::vector<double> initial_state() const override { return {}; }
  Vector6 update(const double*, const Vector6& strain, double dt_s, double, double*,
                 Matrix6* tangent) const override {
    if (!(dt_s >= 0.0)) throw core::UsageError(description_ + ": the time step must be ≥ 0");
    if (tangent) *tangent = C_;
    return C_ * strain;
  }
  ComplexMatrix6 complex_stiffness(double, double) const override {
    return C_.cast<std::complex<double>>();
  }
  bool symmetric_tangent() const override { return isotropic_in_plane_; }

 private:
  Matrix6 C_;
  std::string description_;
  bool isotropic_in_plane_ = false;
};

}  // namespace

MaterialPointPtr elastic_point(const Matrix6& stiffness, std::string description) {
  return std::make_shared<ElasticPoint>(stiffness, std::move(description));
}

MaterialPointPtr elastic_equivalent(const MaterialPoint& point, double frequency_Hz,
                                    double temperature_C) {
  require_steady_condition("elastic equivalent", frequency_Hz, temperature_C);
  const Matrix6 C = point.complex_stiffness(frequency_Hz, temperature_C).real();
  nlohmann::json at = {{"frequency_Hz", frequency_Hz}};
  if (!std::isnan(temperature_C)) at["temperature_C"] = temperature_C;
  return elastic_point(C, point.describe() + ", elastic at " + at.dump());
}

}  // namespace fitlib::model::points
