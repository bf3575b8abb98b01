#pragma once
// Private: a material point that can compute only the tangent's in-plane columns 0, 1, 5 (ε11,
// ε22, γ12), all plane strain reads (model::first_piola's in-plane path, the segment FE). Fritzson's
// point differentiates by forward-mode AD: a Jet of four lanes (three seeded) is two SSE packets
// per derivative vector against the six-lane Jet's three (docs/segment.md "Cost (reference)").
// A point without it gives the full tangent.
#include "fitlib/model/material_point.hpp"

namespace fitlib::model {

class InPlaneTangent {
 public:
  // As MaterialPoint::update with a tangent; its columns other than 0, 1, 5 are zero.
  virtual Vector6 update_in_plane(const double* state_n, const Vector6& strain, double dt_s, double temperature_C,
                                  double* state_next, Matrix6& tangent) const = 0;

 protected:
  ~InPlaneTangent() = default;
};

}  // namespace fitlib::model
