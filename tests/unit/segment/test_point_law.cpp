// The segment's materials through the material-point contract: P = F U⁻¹ τ_U U⁻¹ and dP/dF
// (model/first_piola.hpp) against central differences, for an isotropic and a non-coaxial
// (orthotropic) point, a viscoelastic point over a step, and the element tangent built from them.
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../../fitlib/src/segment/element.hpp"
#include "fitlib/model/first_piola.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/point_law.hpp"

using namespace fitlib;

namespace {

model::MaterialPointPtr point_of(const std::string& kind, const nlohmann::json& options, std::vector<double> values) {
  const model::ModelPtr m = model::make_model(kind, options);
  return model::make_material_point(*m, values);
}

model::MaterialPointPtr ortho() {
  return point_of("elastic-ortho", nlohmann::json::object(), {5.0, 8.0, 200.0, 0.4, 0.01, 0.01, 2.0, 3.0, 3.5});
}
model::MaterialPointPtr prony() {
  return point_of("prony", {{"mode", "shear"}, {"bulk_modulus", true}, {"terms", 3}},
                  {1.0, 2.0, 1.5, 0.8, 0.01, 0.1, 0.5, 500.0});
}
// Fritzson's anisotropic model (damage, three parts; default options: its own time-domain update).
const std::vector<double> kMaterial1{4000.0, 2.5, 2.0, 0.21, 0.008, 2.5, 0.25, 0.6, -2.0, 0.5, 0.5, 0.0065, 0.008,
                                     0.6, 10.0, 8.0, 0.7, 0.008, 2.5, 0.4, 0.5, -2.2, 0.5, 0.5, 0.006, 0.008,
                                     1.2, 1.0, 0.1, 0.008, 2.5, 0.35, 0.6, -2.0, 0.5, 0.5, 0.006, 0.008};
model::MaterialPointPtr fritzson(const model::PointOptions& options = {}) {
  return model::make_material_point(*model::make_model("fritzson", {{"reference_C", 23.0}}), kMaterial1, options);
}

// Central difference of P(F) against the analytic dP/dF, relative to the tangent's size; `in_plane`:
// the plane-strain path and its in-plane rows and columns only.
double tangent_error(const model::MaterialPoint& point, const std::vector<double>& state, const Eigen::Matrix3d& F,
                     double dt, model::TangentColumns columns = model::TangentColumns::all) {
  std::vector<double> next(point.state_size());
  const auto r = model::first_piola(point, state.data(), F, dt, NAN, next.data(), columns);
  const int n = columns == model::TangentColumns::in_plane ? 2 : 3;
  const double h = 1e-6;
  double err = 0.0;
  for (int k = 0; k < n; ++k)
    for (int L = 0; L < n; ++L) {
      Eigen::Matrix3d Fp = F, Fm = F;
      Fp(k, L) += h, Fm(k, L) -= h;
      const Eigen::Matrix3d dP = (model::first_piola(point, state.data(), Fp, dt, NAN, next.data(), model::TangentColumns::none).P -
                                  model::first_piola(point, state.data(), Fm, dt, NAN, next.data(), model::TangentColumns::none).P) /
                                 (2 * h);
      for (int i = 0; i < n; ++i)
        for (int J = 0; J < n; ++J) err = std::max(err, std::abs(dP(i, J) - r.dP_dF(3 * i + J, 3 * k + L)));
    }
  return err / r.dP_dF.cwiseAbs().maxCoeff();
}

Eigen::Matrix3d general_F() {
  Eigen::Matrix3d F;
  F << 1.12, 0.21, -0.05, -0.13, 0.93, 0.04, 0.02, -0.03, 1.05;
  return F;
}

}  // namespace

TEST(SegmentPointLaw, FirstPiolaTangentMatchesCentralDifferences) {
  for (const auto& point : std::vector<model::MaterialPointPtr>{point_of("elastic-iso", nlohmann::json::object(), {10.0, 0.45}), ortho()}) {
    const std::vector<double> state = point->initial_state();
    EXPECT_LT(tangent_error(*point, state, general_F(), 0.0), 1e-7) << point->describe();
    // Repeated stretches (a rotation times an isotropic stretch): the divided differences' limits.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT(tangent_error(*point, state, 1.05 * R, 0.0), 1e-7) << point->describe();
    EXPECT_LT(tangent_error(*point, state, Eigen::Matrix3d::Identity(), 0.0), 1e-7) << point->describe();
  }
}

TEST(SegmentPointLaw, PlaneStrainTangentIsSmoothAcrossTheNearlyRepeatedStretchSwitch) {
  // ½ ln c's divided difference switches to its series where c0/c1 − 1 < 10⁻⁶ (first_piola.cpp), and
  // the eigenvector angle's half-angle formula is singular as C2 → a multiple of I. Central
  // differences with h = 10⁻⁶ straddle both, from gaps of 10⁻⁷ to 10⁻³, for a non-coaxial point.
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(0.4).toRotationMatrix();
  const auto point = ortho();
  for (const double gap : {1e-7, 5e-7, 1e-6, 2e-6, 1e-5, 1e-3}) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F.topLeftCorner<2, 2>() = R * Eigen::Vector2d(0.9 * std::sqrt(1.0 + gap), 0.9).asDiagonal();  // c0/c1 = 1 + gap
    EXPECT_LT(tangent_error(*point, point->initial_state(), F, 0.0, model::TangentColumns::in_plane), 1e-8) << "gap " << gap;
  }
}

TEST(SegmentPointLaw, ViscoelasticTangentOverAStepMatchesCentralDifferences) {
  const auto point = prony();
  std::vector<double> state = point->initial_state(), next(point->state_size());
  Eigen::Matrix3d F1 = Eigen::Matrix3d::Identity();
  F1(0, 1) = 0.1, F1(1, 1) = 0.97;
  model::first_piola(*point, state.data(), F1, 0.05, NAN, next.data(), model::TangentColumns::none);
  state.swap(next);  // a loaded, partly relaxed state
  EXPECT_LT(tangent_error(*point, state, general_F(), 0.02), 1e-7);
}

TEST(SegmentPointLaw, KirchhoffStressIsTheContractsRotatedStress) {
  // τ = P Fᵀ must equal update_deformation's R τ_U Rᵀ (non-coaxial, anisotropic point).
  const auto point = ortho();
  const std::vector<double> s = point->initial_state();
  std::vector<double> next(point->state_size());
  const Eigen::Matrix3d F = general_F();
  const auto r = model::first_piola(*point, s.data(), F, 0.0, NAN, next.data(), model::TangentColumns::none);
  const Eigen::Matrix3d tau = point->update_deformation(s.data(), F, 0.0, NAN, next.data());
  EXPECT_LT((r.P * F.transpose() - tau).cwiseAbs().maxCoeff(), 1e-12 * tau.cwiseAbs().maxCoeff());
}

TEST(SegmentPointLaw, PlaneStrainClosedFormAgreesWithTheGeneralThreeByThreePath) {
  // F = diag(F2, 1) takes the closed-form 2 × 2 spectrum (in-plane columns or none); the general
  // path (all columns, Eigen's 3 × 3 solver) is the independent reference: P, τ_U and the in-plane
  // columns of dP/dF agree to round-off, also at repeated stretches. Fritzson's point gives the
  // plane path only its in-plane tangent columns (a Jet of four lanes against the general path's six).
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear.topLeftCorner<2, 2>() << 1.12, 0.21, -0.13, 0.93;
  for (const auto& point : std::vector<model::MaterialPointPtr>{ortho(), prony(), fritzson()})
    for (const Eigen::Matrix3d& F : {shear, Eigen::Matrix3d(0.97 * R), Eigen::Matrix3d(Eigen::Matrix3d::Identity())}) {
      const std::vector<double> state = point->initial_state();
      std::vector<double> next(point->state_size());
      const auto general = model::first_piola(*point, state.data(), F, 0.01, NAN, next.data(), model::TangentColumns::all);
      const auto plane = model::first_piola(*point, state.data(), F, 0.01, NAN, next.data(), model::TangentColumns::in_plane);
      const double P_size = general.P.cwiseAbs().maxCoeff() + 1e-300, A_size = general.dP_dF.cwiseAbs().maxCoeff();
      EXPECT_LT((plane.P - general.P).cwiseAbs().maxCoeff(), 1e-12 * P_size) << point->describe() << "\n" << F;
      EXPECT_LT((plane.stress_unrotated - general.stress_unrotated).cwiseAbs().maxCoeff(), 1e-12 * P_size);
      for (int k = 0; k < 2; ++k)
        for (int L = 0; L < 2; ++L)
          EXPECT_LT((plane.dP_dF.col(3 * k + L) - general.dP_dF.col(3 * k + L)).cwiseAbs().maxCoeff(), 1e-11 * A_size)
              << point->describe() << " column " << k << L << "\n" << F;
      EXPECT_EQ(plane.dP_dF.col(2).cwiseAbs().maxCoeff(), 0.0);  // columns not asked stay zero
    }
}

TEST(SegmentPointLaw, PlaneStrainClosedFormIsExactAtAHundredToOneStretch) {
  // F = R diag(10, 0.1, 1): U = diag(10, 0.1, 1) and ln U known exactly, so τ_U = C ln U and
  // P = R τ_U U⁻¹. The closed form's smaller eigenvalue comes from det C = J² (no cancellation).
  const auto point = ortho();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d U(10.0, 0.1, 1.0);
  model::Vector6 lnU;
  lnU << std::log(10.0), std::log(0.1), 0.0, 0.0, 0.0, 0.0;
  std::vector<double> next;
  const auto r = model::first_piola(*point, nullptr, R * U.asDiagonal(), 0.0, NAN, next.data(), model::TangentColumns::none);
  const model::Vector6 tau_v = point->update(nullptr, lnU, 0.0, NAN, nullptr, nullptr);
  Eigen::Matrix3d tau;
  tau << tau_v[0], tau_v[5], tau_v[4], tau_v[5], tau_v[1], tau_v[3], tau_v[4], tau_v[3], tau_v[2];
  const Eigen::Matrix3d P = R * tau * U.cwiseInverse().asDiagonal();
  EXPECT_LT((r.stress_unrotated - tau_v).cwiseAbs().maxCoeff(), 1e-13 * tau_v.cwiseAbs().maxCoeff());
  EXPECT_LT((r.P - P).cwiseAbs().maxCoeff(), 1e-13 * P.cwiseAbs().maxCoeff());
}

namespace {

// Largest difference between an element's tangent and central differences of its internal force,
// relative to the tangent's largest entry.
double element_tangent_error(const segment::PlaneStrainLaw& law, const std::vector<Eigen::Vector2d>& X, int order,
                             bool f_bar) {
  std::vector<Eigen::Vector2d> u;
  for (std::size_t a = 0; a < X.size(); ++a) u.push_back({0.05 * X[a].y() + 0.01 * a, -0.04 * X[a].x() + 0.003 * a * a});
  const auto rule = segment::detail::gauss_rule(order);
  std::vector<double> state;
  for (std::size_t q = 0; q < rule.size(); ++q)
    for (double v : law.initial_state()) state.push_back(v);
  std::vector<double> next(state.size());
  const segment::detail::ElementStep step{state.data(), next.data(), 0.02, NAN};
  segment::detail::ElementVector f, fp, fm;
  segment::detail::ElementMatrix K;
  EXPECT_TRUE(segment::detail::element_response(X, u, law, rule, step, f, &K, nullptr, f_bar));
  const double h = 1e-7;
  double err = 0.0;
  for (std::size_t b = 0; b < X.size(); ++b)
    for (int k = 0; k < 2; ++k) {
      auto up = u, um = u;
      up[b][k] += h, um[b][k] -= h;
      segment::detail::element_response(X, up, law, rule, step, fp, nullptr, nullptr, f_bar);
      segment::detail::element_response(X, um, law, rule, step, fm, nullptr, nullptr, f_bar);
      err = std::max(err, ((fp - fm) / (2 * h) - K.col(2 * b + k)).cwiseAbs().maxCoeff());
    }
  return err / K.cwiseAbs().maxCoeff();
}

const std::vector<Eigen::Vector2d> kDistortedQ8 = {{0, 0},      {1.2, 0.1}, {1.1, 0.9},  {-0.1, 1.0},
                                                   {0.6, 0.02}, {1.2, 0.5}, {0.5, 0.97}, {-0.05, 0.5}};

}  // namespace

TEST(SegmentPointLaw, ElementTangentMatchesCentralDifferencesOfItsInternalForce) {
  // A distorted 8-node element, orthotropic contract point, reduced and full integration.
  const segment::ContractLaw law(ortho());
  for (int order : {2, 3}) EXPECT_LT(element_tangent_error(law, kDistortedQ8, order, false), 1e-6) << "order " << order;
}

TEST(SegmentPointLaw, FbarElementTangentMatchesCentralDifferencesOfItsInternalForce) {
  // dF̄ = α[dF + ½F(dJ̄/J̄ − dJ/J)] (docs/segment.md §Element choice): 8 nodes (J̄ from the 2×2
  // points) and 4 nodes (J̄ at the centre), an orthotropic and a viscoelastic point over a step.
  const segment::ContractLaw ortho_law(ortho()), prony_law(prony());
  const std::vector<Eigen::Vector2d> q4(kDistortedQ8.begin(), kDistortedQ8.begin() + 4);
  EXPECT_LT(element_tangent_error(ortho_law, kDistortedQ8, 3, true), 1e-6);
  EXPECT_LT(element_tangent_error(prony_law, kDistortedQ8, 3, true), 1e-6);
  EXPECT_LT(element_tangent_error(ortho_law, q4, 2, true), 1e-6);
}

TEST(SegmentPointLaw, HenckyContractPointAgreesWithStVenantKirchhoffAtSmallStrain) {
  // Both reduce to linear elasticity: at ε ~ 1e-4 the stresses agree to O(ε²) relative.
  const double E = 20.0, nu = 0.49;
  const segment::ContractLaw hencky(point_of("elastic-iso", nlohmann::json::object(), {E, nu}));
  const auto svk = segment::make_elastic(segment::ElasticLaw::st_venant_kirchhoff, E, nu);
  Eigen::Matrix2d F;
  F << 1.0 + 1e-4, 0.5e-4, -0.3e-4, 1.0 - 0.7e-4;
  const auto a = hencky.respond(F), b = svk->respond(F);
  EXPECT_LT((a.P - b.P).cwiseAbs().maxCoeff(), 1e-3 * b.P.cwiseAbs().maxCoeff());
  EXPECT_NEAR(a.sigma33_MPa, b.sigma33_MPa, 1e-3 * std::abs(b.sigma33_MPa));
}

// The typed capability behind the LDLᵀ path: an elastic point isotropic in the 1–2 plane says its
// tangent is symmetric, and its plane-strain dP/dF is major-symmetric at a general F — the
// isotropic card and the elastic equivalent of Fritzson's anisotropic material 1 (cord-direction
// parts: transversely isotropic about axis 3); an in-plane orthotropic elastic point (τ_U = C ln U
// not coaxial with U: no energy), a viscoelastic and a complete Fritzson point say no, and the
// orthotropic tangent is measurably unsymmetric.
TEST(SegmentPointLaw, OnlyElasticPointsIsotropicInThePlaneSayTheirTangentIsSymmetric) {
  const auto iso = point_of("elastic-iso", nlohmann::json::object(), {20.0, 0.49});
  model::PointOptions elastic;
  elastic.fidelity = core::Fidelity::elastic;
  elastic.frequency_Hz = 10.0;
  const auto fritzson_elastic = fritzson(elastic);
  auto asymmetry = [](const model::MaterialPointPtr& p) {
    const segment::PointResponse r = segment::ContractLaw(p).respond(general_F().topLeftCorner<2, 2>());
    return (r.A - r.A.transpose()).cwiseAbs().maxCoeff() / r.A.cwiseAbs().maxCoeff();
  };
  for (const auto& p : {iso, fritzson_elastic}) {
    EXPECT_TRUE(p->symmetric_tangent()) << p->describe();
    EXPECT_TRUE(segment::ContractLaw(p).symmetric_tangent());
    EXPECT_LT(asymmetry(p), 1e-9) << p->describe();
  }
  EXPECT_FALSE(ortho()->symmetric_tangent());
  EXPECT_GT(asymmetry(ortho()), 1e-4);
  EXPECT_FALSE(prony()->symmetric_tangent());
  EXPECT_FALSE(segment::ContractLaw(prony()).symmetric_tangent());
  EXPECT_FALSE(fritzson()->symmetric_tangent());
}
