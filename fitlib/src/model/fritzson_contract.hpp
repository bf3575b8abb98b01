#pragma once
// Private: Fritzson's integrator behind the material-point contract.
#include <vector>

#include "fitlib/model/material_point.hpp"

namespace fitlib::model::fritzson {

class MaterialPoint;
// MaterialPoint::update_flat with only the tangent's columns 0, 1, 5 (the others zero), on a Jet of
// four lanes, three seeded (fritzson_point.cpp; in_plane_point.hpp).
Vector6 update_flat_in_plane(const MaterialPoint& point, const double* state, const Vector6& strain, double dt_s,
                             double temperature_C, double* next, Matrix6& tangent);

model::MaterialPointPtr make_contract_point(std::vector<double> p, bool anisotropic,
                                            double reference_C, const PointOptions& options);

}  // namespace fitlib::model::fritzson
