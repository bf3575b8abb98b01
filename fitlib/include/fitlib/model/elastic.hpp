#pragma once
// Linear elastic cards (docs/model.md §"Elastic cards"), for the segment's elastic fidelity and
// materials without test data:
//   elastic-iso    E (MPa), nu                                   isotropic
//   elastic-ortho  E1, E2, E3 (MPa), nu12, nu13, nu23, G12, G13, G23 (MPa)
//                  orthotropic in material axes, ν_ij = −ε_j/ε_i under uniaxial stress along i
// No options. Moduli have no loss and no temperature dependence.
#include <nlohmann/json.hpp>
#include <string>

#include "fitlib/model/model.hpp"

namespace fitlib::model {

bool is_elastic_kind(const std::string& kind);
ModelPtr make_elastic_model(const std::string& kind, const nlohmann::json& options);

}  // namespace fitlib::model
