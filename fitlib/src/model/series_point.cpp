// The material point of any shear model that is an exact Maxwell or Kelvin series.
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/time_series.hpp"
#include "points.hpp"

namespace fitlib::model {

MaterialPointPtr series_point(std::shared_ptr<const Model> model, std::vector<double> values,
                              const PointOptions& options) {
  const std::string name = model->kind() + " (series point)";
  if (model->native_mode() != TestMode::shear)
    throw core::UsageError(name + ": the 3-D series point needs a shear card");
  MaxwellSeries shear;
  KelvinSeries kelvin;
  if (!model->maxwell_series(values.data(), &shear)) {
    if (!model->kelvin_series(values.data(), &kelvin))
      throw core::UsageError(name + ": the model is neither a Maxwell nor a Kelvin series");
    shear = kelvin.to_maxwell();
  }
  const double K = std::isnan(options.bulk_modulus_MPa) ? model->bulk_modulus(values.data())
                                                        : options.bulk_modulus_MPa;
  if (!(K > 0.0)) throw core::UsageError(name + ": a material point needs a bulk modulus K > 0");
  auto temperature = [model, values](double T) { return model->temperature_factors(values.data(), T); };
  const auto point = points::linear_viscoelastic_point(std::move(shear), MaxwellSeries{K, {}, {}},
                                                       std::move(temperature), name);
  if (options.fidelity == core::Fidelity::elastic)
    return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
  return point;
}

}  // namespace fitlib::model
