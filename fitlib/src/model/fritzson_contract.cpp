// Fritzson's model behind the material-point contract: the existing integrator
// (fritzson_point.cpp) with its state flattened, and its small-amplitude complex stiffness.
#include <nlohmann/json.hpp>

#include "fitlib/core/units.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "fritzson_contract.hpp"
#include "points.hpp"

namespace fitlib::model::fritzson {
namespace {

// Flat layout of MaterialState: time, strain (6), deviatoric strain integral (6), driver
// amplitudes (3), last oscillating drivers (3), isotropic Maxwell stresses (5 × 6), A1 (5),
// A2 (5 × 2).
constexpr std::size_t kStateSize = 1 + 6 + 6 + 3 + 3 + 30 + 5 + 10;

void unpack(const double* x, MaterialState& s) {
  s.time_s = *x++;
  for (int i = 0; i < 6; ++i) s.strain[i] = *x++;
  for (int i = 0; i < 6; ++i) s.dev_strain_integral[i] = *x++;
  for (double& v : s.driver_amplitude) v = *x++;
  for (double& v : s.driver_oscillating) v = *x++;
  for (auto& v : s.viscous_I)
    for (int i = 0; i < 6; ++i) v[i] = *x++;
  for (double& v : s.viscous_A1) v = *x++;
  for (auto& v : s.viscous_A2) v[0] = *x++, v[1] = *x++;
}

void pack(const MaterialState& s, double* x) {
  *x++ = s.time_s;
  for (int i = 0; i < 6; ++i) *x++ = s.strain[i];
  for (int i = 0; i < 6; ++i) *x++ = s.dev_strain_integral[i];
  for (double v : s.driver_amplitude) *x++ = v;
  for (double v : s.driver_oscillating) *x++ = v;
  for (const auto& v : s.viscous_I)
    for (int i = 0; i < 6; ++i) *x++ = v[i];
  for (double v : s.viscous_A1) *x++ = v;
  for (const auto& v : s.viscous_A2) *x++ = v[0], *x++ = v[1];
}

// Deviatoric projector b with e_k = b·ε for the A1 measure e3, and the spread a = (−½, −½, 1):
// s = 2M e3 a adds 2M a bᵀ = (4/3)M a aᵀ to the stiffness (fritzson.md, A1 part).
class FritzsonContractPoint final : public model::MaterialPoint {
 public:
  FritzsonContractPoint(std::vector<double> p, bool anisotropic, double reference_C, Scheme scheme)
      : point_(std::move(p), anisotropic, reference_C, scheme), reference_C_(reference_C) {}

  std::string describe() const override {
    return std::string(point_.anisotropic() ? "fritzson" : "fritzson-iso") +
           (point_.scheme() == Scheme::exponential ? " (exponential)" : " (backward Euler)");
  }
  std::size_t state_size() const override { return kStateSize; }
  std::vector<double> initial_state() const override {
    std::vector<double> x(kStateSize);
    pack(MaterialState(), x.data());
    return x;
  }

  Vector6 update(const double* state_n, const Vector6& strain, double dt_s, double temperature_C,
                 double* state_next, Matrix6* tangent) const override {
    // Scratch states kept per thread: constructing (zeroing) two per call would cost more than
    // the copies (docs/model.md, contract cost).
    thread_local MaterialState s, next;
    unpack(state_n, s);
    const Vector6 stress = point_.update(s, strain, dt_s, temperature_C, next, tangent);
    pack(next, state_next);
    return stress;
  }

  // Virgin material (no damage driver: h1 = 1, h2 = β2), mean strain zero: each part adds its
  // dynamic modulus M* (part_moduli) on its own strain measure.
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
      options.fritzson_exponential ? Scheme::exponential : Scheme::backward_euler);
  if (options.fidelity == PointOptions::Fidelity::elastic)
    return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
  return point;
}

}  // namespace fitlib::model::fritzson
