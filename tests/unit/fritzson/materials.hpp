#pragma once
// The documented "true" parameter sets of the synthetic materials 1 and 2 (datasets/README.md,
// docs/fritzson.md §6) and the generator of their dynamic-test tables (Report V test designs).
#include <string>
#include <vector>

#include "fitlib/data/table.hpp"

namespace fritzson_test {

// Material 1: transversely isotropic bottom rubber (model "fritzson", 38 parameters).
std::vector<double> material1_parameters();
// Material 2: isotropic cushion rubber (model "fritzson-iso", 14 parameters).
std::vector<double> material2_parameters();
constexpr double kReferenceC = 23.0;

// The synthetic table of material 1 or 2 (seeded scatter), rows in design order.
fitlib::data::DynamicTestTable material_table(int material);

}  // namespace fritzson_test
