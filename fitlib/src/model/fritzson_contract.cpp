// Fritzson's model behind the material-point contract: the existing integrator
// (fritzson_point.cpp) with its state flattened, and its small-amplitude complex stiffness.
#include <nlohmann/json.hpp>

#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "fritzson_contract.hpp"
#include "points.hpp"

namespace fitlib::model::fritzson {
namespace {

// The integrator of fritzson_point.cpp on the contract's flat state (FlatState, no copies).
class FritzsonContractPoint final : public model::MaterialPoint {
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

  // Virgin material (no damage driver: h1 = 1, h2 = β2), mean strain zero: each part adds its
  // dynamic modulus M* (part_moduli) on its own strain measure. A1: e3 = b·ε with
  // b = (2/3)a and the stress spread a = (−½, −½, 1), so s = 2M* e3 a adds (4/3)M* a aᵀ.
  ComplexMatrix6 complex_stiffness(double frequency_Hz, double temperature_C) const override {
    const double* p = point_.parameters().data();
    const double omega = core::angular_frequency(frequency_Hz);
    auto modulus = [&](int offset) {
      const PartFactors<double> f = part_factors(p + offset, 0.0, temperature_C, reference_C_);
      return part_moduli(p + offset, f, omega).dynamic;
    };
    using C = std::complex<double>;
    ComplexMatrix6 K = points::isotropic_stiffness<C>(p[kK], modulus(kPartI));
    if (point_.anisotropic()) {
      const C a1 = modulus(kPartA1), a2 = modulus(kPartA2);
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
  if (options.fidelity == PointOptions::Fidelity::elastic)
    return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
  return point;
}

}  // namespace fitlib::model::fritzson
