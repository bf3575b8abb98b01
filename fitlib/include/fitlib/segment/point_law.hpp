#pragma once
// The segment's materials from the material-point contract (docs/segment.md §Materials): an
// adapter that turns a model::MaterialPoint (τ_U from ln U, tangent dτ_U/d(ln U)) into the
// element's P(F) and dP/dF (model/first_piola.hpp), and the point of a card per role at the
// segment's fidelity.
#include <vector>

#include "fitlib/core/fidelity.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/elastic.hpp"

namespace fitlib::segment {

class ContractLaw final : public PlaneStrainLaw {
 public:
  explicit ContractLaw(model::MaterialPointPtr point);
  using PlaneStrainLaw::respond;
  std::size_t state_size() const override { return point_->state_size(); }
  std::vector<double> initial_state() const override { return point_->initial_state(); }
  // As the point says (model::MaterialPoint::symmetric_tangent: an isotropic elastic point).
  bool symmetric_tangent() const override { return point_->symmetric_tangent(); }
  PointResponse respond(const Matrix2& F, const PointStep& step) const override;
  const model::MaterialPoint& point() const { return *point_; }

 private:
  model::MaterialPointPtr point_;
};

struct RoleMaterialOptions {
  // The segment's levels (core::Fidelity; issue 11 item 5): `elastic` — the card's elastic
  // equivalent (storage stiffness) at the scene's temperature and load frequency; `complete` — the
  // card's full model. `beam` has no material point (make_material_point refuses it).
  core::Fidelity fidelity = core::Fidelity::complete;
  double temperature_C = 20.0;   // elastic fidelity: where the storage stiffness is taken
  double frequency_Hz = 10.0;    // elastic fidelity: the load cycle's frequency
  double bulk_modulus_MPa = std::numeric_limits<double>::quiet_NaN();  // for shear cards without K
  // complete fidelity, models with damage: the model's own (implicit) update, or damage lagged by
  // one increment (model::PointOptions::DamageUpdate; docs/segment.md §Cost, "Complete level").
  model::PointOptions::DamageUpdate damage_update = model::PointOptions::DamageUpdate::implicit;
  // complete fidelity, models with damage: model::PointOptions::damage_driver_hold.
  std::vector<double> damage_driver_hold;
};

// The point of a card (its model and parameter values) for one role.
model::MaterialPointPtr role_point(const model::Model& model, const std::vector<double>& values,
                                   const RoleMaterialOptions& options);

}  // namespace fitlib::segment
