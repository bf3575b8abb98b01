#pragma once
// Private: Fritzson's integrator behind the material-point contract.
#include <vector>

#include "fitlib/model/material_point.hpp"

namespace fitlib::model::fritzson {

model::MaterialPointPtr make_contract_point(std::vector<double> p, bool anisotropic,
                                            double reference_C, const PointOptions& options);

}  // namespace fitlib::model::fritzson
