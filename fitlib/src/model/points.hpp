#pragma once
// Private: the material points behind Model::material_point (docs/model.md §"Material point").
#include <functional>
#include <string>
#include <vector>

#include "fitlib/model/material_point.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::model::points {

// Isotropic stiffness in Voigt form (engineering shear strains) from bulk K and shear G:
// C = K 1⊗1 + 2G I_dev, shear diagonal G. S is double or std::complex<double>.
template <typename S>
Eigen::Matrix<S, 6, 6> isotropic_stiffness(S K, S G) {
  Eigen::Matrix<S, 6, 6> C = Eigen::Matrix<S, 6, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) C(i, j) = K - S(2.0 / 3.0) * G;
    C(i, i) = K + S(4.0 / 3.0) * G;
    C(3 + i, 3 + i) = G;
  }
  return C;
}

// Linear elastic point σ = C ε (no state, no temperature dependence).
MaterialPointPtr elastic_point(const Matrix6& stiffness, std::string description);

// The elastic equivalent of a point: Re C*(f, T) (storage stiffness).
MaterialPointPtr elastic_equivalent(const MaterialPoint& point, double frequency_Hz,
                                    double temperature_C);

// Isotropic linear viscoelastic point: deviatoric stress from the shear Maxwell series G(t),
// mean stress from the bulk series K(t) (no terms = elastic K); time–temperature superposition
// through `temperature` (reduced time increment Δt/a_T, moduli × scale).
using TemperatureFunction = std::function<TemperatureFactors(double temperature_C)>;
MaterialPointPtr linear_viscoelastic_point(MaxwellSeries shear, MaxwellSeries bulk,
                                           TemperatureFunction temperature,
                                           std::string description);

}  // namespace fitlib::model::points
