// Fritzson's model behind the material-point contract: the existing integrator
// (fritzson_point.cpp) with its state flattened, and its small-amplitude complex stiffness.
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "fritzson_contract.hpp"
#include "in_plane_point.hpp"
#include "points.hpp"

namespace fitlib::model::fritzson {
namespace {

// The integrator of fritzson_point.cpp on the contract's flat state (FlatState, no copies).
class FritzsonContractPoint final : public model::MaterialPoint, public model::InPlaneTangent {
 public:
  FritzsonContractPoint(std::vector<double> p, bool anisotropic, double reference_C, Scheme scheme,
                        DamageUpdate damage_update)
      : point_(std::move(p), anisotropic, reference_C, scheme, damage_update), reference_C_(reference_C) {}
  void hold_damage_beyond(const std::vector<double>& ceiling) { point_.hold_damage_beyond(ceiling); }

  std::string describe() const override {
    return std::string(point_.anisotropic() ? "fritzson" : "fritzson-iso") +
           (point_.scheme() == Scheme::exponential ? " (exponential" : " (backward Euler") +
           (point_.damage_update() == DamageUpdate::lagged ? ", lagged damage" : "") +
           (point_.damage_held() ? ", damage held at its tests' drivers" : "") +
           ")";
  }
  std::size_t state_size() const override { return kFlatStateSize; }
  // The virgin MaterialState is all zeros.
  std::vector<double> initial_state() const override { return std::vector<double>(kFlatStateSize, 0.0); }

  Vector6 update(const double* state_n, const Vector6& strain, double dt_s, double temperature_C,
                 double* state_next, Matrix6* tangent) const override {
    return point_.update_flat(state_n, strain, dt_s, temperature_C, state_next, tangent);
  }
  Vector6 update_in_plane(const double* state_n, const Vector6& strain, double dt_s, double temperature_C,
                          double* state_next, Matrix6& tangent) const override {
    return update_flat_in_plane(point_, state_n, strain, dt_s, temperature_C, state_next, tangent);
  }

  // Virgin material (no damage driver: h1 = 1, h2 = β2), mean strain zero.
  ComplexMatrix6 complex_stiffness(double frequency_Hz, double temperature_C) const override {
    return steady_stiffness(frequency_Hz, temperature_C, {0.0, 0.0, 0.0});
  }

  // The steady response once the damage drivers have saturated at `drivers` (I, A1, A2; held at
  // the point's hold): each part adds its dynamic modulus M* (part_moduli) on its own strain
  // measure. A1: e3 = b·ε with b = (2/3)a and the stress spread a = (−½, −½, 1), so s = 2M* e3 a
  // adds (4/3)M* a aᵀ. The shear test's storage modulus at γ is C66 with drivers (γ/√2, 0, 0),
  // the model's own moduli() (docs/fritzson.md §3).
  ComplexMatrix6 steady_stiffness(double frequency_Hz, double temperature_C, const std::array<double, 3>& drivers) const {
    const double* p = point_.parameters().data();
    const double omega = core::angular_frequency(frequency_Hz);
    auto modulus = [&](int offset, int part) {
      const double driver = point_.held_driver(part, drivers[part]);
      const PartFactors<double> f = part_factors(p + offset, driver, temperature_C, reference_C_);
      return part_moduli(p + offset, f, omega).dynamic;
    };
    using C = std::complex<double>;
    ComplexMatrix6 K = points::isotropic_stiffness<C>(p[kK], modulus(kPartI, 0));
    if (point_.anisotropic()) {
      const C a1 = modulus(kPartA1, 1), a2 = modulus(kPartA2, 2);
      const double a[3] = {-0.5, -0.5, 1.0};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) K(i, j) += (4.0 / 3.0) * a1 * a[i] * a[j];
      K(3, 3) += a2;  // s23 = M* γ23 (A2), likewise 13
      K(4, 4) += a2;
    }
    return K;
  }

 private:
  fritzson::MaterialPoint point_;
  double reference_C_;
};

}  // namespace

model::MaterialPointPtr make_contract_point(std::vector<double> p, bool anisotropic,
                                            double reference_C, const PointOptions& options) {
  const auto point = std::make_shared<FritzsonContractPoint>(
      std::move(p), anisotropic, reference_C,
      options.fritzson_exponential ? Scheme::exponential : Scheme::backward_euler, options.damage_update);
  point->hold_damage_beyond(options.damage_driver_hold);
  if (options.fidelity != core::Fidelity::elastic) return point;
  if (!options.strain_amplitude)
    return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
  // The elastic equivalent at an amplitude: the storage stiffness of the steady cycle whose damage
  // drivers that oscillation reaches (PointOptions::strain_amplitude).
  require_steady_condition("fritzson elastic equivalent", options.frequency_Hz, options.temperature_C);
  if (!options.strain_amplitude->allFinite())
    throw core::UsageError("fritzson elastic equivalent: the strain amplitude must be finite");
  const std::array<double, 3> drivers = steady_drivers(*options.strain_amplitude);
  const Matrix6 C = point->steady_stiffness(options.frequency_Hz, options.temperature_C, drivers).real();
  return points::elastic_point(C, point->describe() + ", elastic at " + core::format_number(options.frequency_Hz) +
                                      " Hz and damage drivers " + core::format_number(drivers[0], 4) +
                                      (anisotropic ? ", " + core::format_number(drivers[1], 4) + ", " +
                                                         core::format_number(drivers[2], 4)
                                                   : std::string()));
}

}  // namespace fitlib::model::fritzson
