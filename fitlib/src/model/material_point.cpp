// What every material point shares: the finite-strain and plane-strain wrappers, restart JSON,
// and the MTest-style driver (docs/model.md §"Material point").
#include "fitlib/model/material_point.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"

namespace fitlib::model {

Vector6 log_strain(const Eigen::Matrix3d& F, Eigen::Matrix3d* rotation) {
  if (!(F.determinant() > 0.0))
    throw core::NumericalError("material point: deformation gradient with det F ≤ 0");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(F.transpose() * F);
  const Eigen::Vector3d lambda = eig.eigenvalues().cwiseSqrt();
  const Eigen::Matrix3d Q = eig.eigenvectors();
  const Eigen::Matrix3d lnU = Q * lambda.array().log().matrix().asDiagonal() * Q.transpose();
  if (rotation) {
    const Eigen::Matrix3d U_inv = Q * lambda.cwiseInverse().asDiagonal() * Q.transpose();
    *rotation = F * U_inv;
  }
  Vector6 e;
  e << lnU(0, 0), lnU(1, 1), lnU(2, 2), 2.0 * lnU(1, 2), 2.0 * lnU(0, 2), 2.0 * lnU(0, 1);
  return e;
}

Eigen::Matrix3d MaterialPoint::update_deformation(const double* state_n, const Eigen::Matrix3d& F,
                                                  double dt_s, double temperature_C,
                                                  double* state_next, Vector6* stress_unrotated,
                                                  Matrix6* tangent) const {
  return log_strain_step(F, stress_unrotated, [&](const Vector6& strain) {
    return update(state_n, strain, dt_s, temperature_C, state_next, tangent);
  });
}

Eigen::Matrix3d rotate_stress(const Vector6& s, const Eigen::Matrix3d& R) {
  Eigen::Matrix3d S;
  S << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return R * S * R.transpose();
}

MaterialPoint::PlaneStrainResult MaterialPoint::update_plane_strain(
    const double* state_n, const Eigen::Vector3d& strain, double dt_s, double temperature_C,
    double* state_next, bool want_tangent) const {
  static constexpr int kInPlane[3] = {0, 1, 5};  // 11, 22, 12
  Vector6 full = Vector6::Zero();
  for (int a = 0; a < 3; ++a) full[kInPlane[a]] = strain[a];
  Matrix6 C;
  const Vector6 s = update(state_n, full, dt_s, temperature_C, state_next,
                           want_tangent ? &C : nullptr);
  PlaneStrainResult out;
  out.stress_33 = s[2];
  out.tangent.setZero();
  for (int a = 0; a < 3; ++a) {
    out.stress[a] = s[kInPlane[a]];
    if (want_tangent)
      for (int b = 0; b < 3; ++b) out.tangent(a, b) = C(kInPlane[a], kInPlane[b]);
  }
  return out;
}

nlohmann::json MaterialPoint::state_to_json(const double* state) const {
  return {{"point", describe()}, {"state", std::vector<double>(state, state + state_size())}};
}

std::vector<double> MaterialPoint::state_from_json(const nlohmann::json& j) const {
  if (!j.is_object() || !j.contains("state") || !j["state"].is_array())
    throw core::UsageError("material point state: expected an object with a 'state' array");
  if (j.contains("point") && j["point"] != describe())
    throw core::UsageError("material point state: written by '" + j["point"].dump() +
                           "', this point is '" + describe() + "'");
  std::vector<double> state;
  for (const auto& v : j["state"]) {
    if (!v.is_number()) throw core::UsageError("material point state: non-numeric entry");
    state.push_back(v.get<double>());
  }
  if (state.size() != state_size())
    throw core::UsageError("material point state: " + std::to_string(state.size()) +
                           " values, this point needs " + std::to_string(state_size()));
  return state;
}

void require_temperature(const std::string& who, double temperature_C) {
  if (std::isinf(temperature_C))
    throw core::UsageError(who + ": the temperature must be finite (NaN = the card's reference)");
}

void require_steady_condition(const std::string& who, double frequency_Hz, double temperature_C) {
  if (!(frequency_Hz > 0.0 && std::isfinite(frequency_Hz)))
    throw core::UsageError(who + ": the frequency must be finite and > 0 Hz");
  require_temperature(who, temperature_C);
}

MaterialPointPtr make_material_point(const Model& model, const std::vector<double>& values,
                                     const PointOptions& options) {
  if (values.size() != model.size())
    throw core::UsageError("material point: " + model.kind() + " needs " +
                           std::to_string(model.size()) + " parameters, got " +
                           std::to_string(values.size()));
  require_finite_parameters(model, values);  // a NaN would reach every stress of the point
  if (options.fidelity == core::Fidelity::beam)
    throw core::UsageError("material point: the beam level has none (elastic or complete)");
  return model.material_point(values.data(), options);
}

}  // namespace fitlib::model
