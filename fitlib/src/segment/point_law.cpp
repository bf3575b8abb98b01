#include "fitlib/segment/point_law.hpp"

#include "fitlib/core/error.hpp"
#include "fitlib/model/first_piola.hpp"

namespace fitlib::segment {

ContractLaw::ContractLaw(model::MaterialPointPtr point) : point_(std::move(point)) {
  if (!point_) throw core::UsageError("segment: a material point is required");
}

// Plane strain: F = [[F2, 0], [0, 1]]; only the in-plane columns of dP/dF are formed.
PointResponse ContractLaw::respond(const Matrix2& F2, const PointStep& step) const {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F.topLeftCorner<2, 2>() = F2;
  const model::FirstPiolaResult r = model::first_piola(*point_, step.state_n, F, step.dt_s, step.temperature_C,
                                                       step.state_next,
                                                       step.tangent ? model::TangentColumns::in_plane
                                                                    : model::TangentColumns::none);
  PointResponse out;
  out.P = r.P.topLeftCorner<2, 2>();
  for (int i = 0; i < 2; ++i)
    for (int J = 0; J < 2; ++J)
      for (int k = 0; k < 2; ++k)
        for (int L = 0; L < 2; ++L) out.A(2 * i + J, 2 * k + L) = r.dP_dF(3 * i + J, 3 * k + L);
  out.sigma33_MPa = r.stress_unrotated[2] / F2.determinant();  // τ33 / J, R leaves e3 fixed
  return out;
}

model::MaterialPointPtr role_point(const model::Model& model, const std::vector<double>& values,
                                   const RoleMaterialOptions& o) {
  model::PointOptions po;
  po.fidelity = o.fidelity;
  po.temperature_C = o.temperature_C;
  po.frequency_Hz = o.frequency_Hz;
  po.bulk_modulus_MPa = o.bulk_modulus_MPa;
  po.damage_update = o.damage_update;
  po.damage_driver_hold = o.damage_driver_hold;
  return model::make_material_point(model, values, po);
}

}  // namespace fitlib::segment
