#include "fitlib/segment/elastic.hpp"

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/point_law.hpp"

#include <nlohmann/json.hpp>

namespace fitlib::segment {
namespace {

int ij(int i, int J) { return 2 * i + J; }

// S = λ tr(E) I + 2μ E with E = ½(FᵀF − I), E33 = 0; P = F S;
// A_iJkL = δ_ik S_JL + F_iM C_MJNL F_kN.
class StVenantKirchhoff final : public PlaneStrainLaw {
 public:
  StVenantKirchhoff(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  PointResponse respond(const Matrix2& F, const PointStep&) const override {
    const Matrix2 E = 0.5 * (F.transpose() * F - Matrix2::Identity());
    const Matrix2 S = lambda_ * E.trace() * Matrix2::Identity() + 2.0 * mu_ * E;
    PointResponse r;
    r.P = F * S;
    r.A.setZero();
    for (int i = 0; i < 2; ++i)
      for (int J = 0; J < 2; ++J)
        for (int k = 0; k < 2; ++k)
          for (int L = 0; L < 2; ++L) {
            double a = (i == k) ? S(J, L) : 0.0;
            // F_iM C_MJNL F_kN with C = λ δ_MJ δ_NL + μ (δ_MN δ_JL + δ_ML δ_JN)
            a += lambda_ * F(i, J) * F(k, L) + mu_ * ((F.row(i).dot(F.row(k))) * (J == L ? 1.0 : 0.0) +
                                                      F(i, L) * F(k, J));
            r.A(ij(i, J), ij(k, L)) = a;
          }
    r.sigma33_MPa = lambda_ * E.trace() / F.determinant();  // S33 with F33 = 1, σ33 = S33/J
    return r;
  }

 private:
  double lambda_, mu_;
};

// W = μ/2 (I1 − 3) − μ ln J + λ/2 (ln J)²: P = μ(F − F⁻ᵀ) + λ ln J F⁻ᵀ.
class NeoHookean final : public PlaneStrainLaw {
 public:
  NeoHookean(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  PointResponse respond(const Matrix2& F, const PointStep&) const override {
    const double J = F.determinant();
    PointResponse r;
    if (!(J > 0.0)) {
      r.P.fill(NAN);
      r.A.fill(NAN);
      return r;
    }
    const Matrix2 Finv = F.inverse(), FinvT = Finv.transpose();
    const double lnJ = std::log(J);
    r.P = mu_ * (F - FinvT) + lambda_ * lnJ * FinvT;
    for (int i = 0; i < 2; ++i)
      for (int J2 = 0; J2 < 2; ++J2)
        for (int k = 0; k < 2; ++k)
          for (int L = 0; L < 2; ++L)
            r.A(ij(i, J2), ij(k, L)) = mu_ * ((i == k && J2 == L) ? 1.0 : 0.0) +
                                       (mu_ - lambda_ * lnJ) * Finv(L, i) * Finv(J2, k) +
                                       lambda_ * FinvT(i, J2) * FinvT(k, L);
    r.sigma33_MPa = lambda_ * lnJ / J;  // τ33 = μ(1 − 1) + λ ln J
    return r;
  }

 private:
  double lambda_, mu_;
};

}  // namespace

PointResponse PlaneStrainLaw::respond(const Matrix2& F) const {
  const std::vector<double> virgin = initial_state();
  std::vector<double> next(virgin.size());
  return respond(F, {virgin.data(), next.data(), 0.0, std::numeric_limits<double>::quiet_NaN()});
}

ElasticLaw elastic_law_from_string(const std::string& name) {
  if (name == "stvk" || name == "st-venant-kirchhoff") return ElasticLaw::st_venant_kirchhoff;
  if (name == "neo-hookean") return ElasticLaw::neo_hookean;
  if (name == "hencky") return ElasticLaw::hencky;
  throw core::UsageError("unknown elastic law '" + name + "' (known: stvk, neo-hookean, hencky)");
}

std::string to_string(ElasticLaw law) {
  switch (law) {
    case ElasticLaw::st_venant_kirchhoff: return "stvk";
    case ElasticLaw::neo_hookean: return "neo-hookean";
    case ElasticLaw::hencky: return "hencky";
  }
  return "?";
}

std::unique_ptr<PlaneStrainLaw> make_elastic(ElasticLaw law, double E_MPa, double nu) {
  if (!(E_MPa > 0.0) || !(nu > -1.0 && nu < 0.5))
    throw core::UsageError("elastic law needs E > 0 and −1 < ν < 0.5");
  const double lambda = E_MPa * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E_MPa / (2.0 * (1.0 + nu));
  if (law == ElasticLaw::st_venant_kirchhoff) return std::make_unique<StVenantKirchhoff>(lambda, mu);
  if (law == ElasticLaw::hencky) {
    const model::ModelPtr iso = model::make_model("elastic-iso", nlohmann::json::object());
    return std::make_unique<ContractLaw>(model::make_material_point(*iso, {E_MPa, nu}));
  }
  return std::make_unique<NeoHookean>(lambda, mu);
}

}  // namespace fitlib::segment
