// Fritzson's model: parameter specs and the complex (steady sinusoidal) form for every test.
// Derivation and line references: docs/fritzson.md §2–3.
#include "fitlib/model/fritzson.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <type_traits>

#include "fitlib/core/error.hpp"
#include "fitlib/model/autodiff_model.hpp"
#include "fitlib/model/fritzson_cases.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "fritzson_contract.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::model::fritzson {
namespace {

using core::ParameterSpec;
using core::Transform;

using core::kPi;

// The 12 constants of one deviatoric part, in PartIndex order.
void add_part(std::vector<ParameterSpec>& specs, const std::string& suffix,
              const std::string& modulus_prefix, bool isotropic, double mean, double dynamic,
              double viscous) {
  auto group = [&](const char* iso_group) { return isotropic ? std::string(iso_group) : suffix; };
  const std::string m = modulus_prefix;
  const std::string mod_suffix = isotropic ? "_I" : "_A";
  specs.push_back({m + mod_suffix + "m", "MPa", 1e-6, 1e4, Transform::log, group("mean"), mean, true});
  specs.push_back({m + mod_suffix + "d", "MPa", 1e-6, 1e4, Transform::log, group("dynamic"), dynamic, true});
  specs.push_back({m + mod_suffix + "v", "MPa", 1e-6, 1e4, Transform::log, group("viscous"), viscous, true});
  const std::string s = "_" + suffix;
  specs.push_back({"tau" + s, "s", 1e-7, 1e3, Transform::log, group("viscous"), 0.01, false});
  specs.push_back({"k" + s, "-", 1.0, 100.0, Transform::log, group("viscous"), 3.0, false});
  // β1 > 0 keeps the elastic moduli positive at any amplitude (uniaxial compliance 1/(2M)).
  specs.push_back({"beta1" + s, "-", 0.01, 1.0, Transform::linear, group("damage"), 0.4, false});
  specs.push_back({"alpha1" + s, "-", 0.05, 3.0, Transform::log, group("damage"), 0.6, false});
  specs.push_back({"mu" + s, "-", -5.0, 0.0, Transform::linear, group("damage"), -2.0, false});
  specs.push_back({"beta2" + s, "-", 0.0, 1.0, Transform::linear, group("damage"), 0.5, false});
  specs.push_back({"alpha2" + s, "-", 0.05, 3.0, Transform::log, group("damage"), 0.6, false});
  specs.push_back({"c1" + s, "1/degC", -0.01, 0.01, Transform::linear, group("temperature"), 0.0, false});
  specs.push_back({"c2" + s, "1/degC", -0.01, 0.01, Transform::linear, group("temperature"), 0.0, false});
}

// Orientation of a test in material axes (1 radial, 2 along the belt, 3 axial = fibres).
struct Orientation {
  int uniaxial_axis = 1;   // 0, 1, 2 for 11, 22, 33
  bool fibre_shear = false;  // shear 13/23 (the A2 part acts)
};

Orientation parse_orientation(const TestCondition& c, bool anisotropic) {
  Orientation o;
  if (c.mode == TestMode::bulk) return o;
  const std::string& label = c.orientation;
  if (label.empty()) {
    if (anisotropic)
      throw core::UsageError(
          "model fritzson (transversely isotropic) needs the orientation of every " +
          std::string(to_string(c.mode)) + " test (11, 22, 33 uniaxial; 12, 13, 23 shear)");
    return o;
  }
  const bool two_digits = label.size() == 2 && label[0] >= '1' && label[0] <= '3' &&
                          label[1] >= '1' && label[1] <= '3';
  if (!two_digits)
    throw core::UsageError("model fritzson: orientation '" + label +
                           "' is not one of 11, 22, 33, 12, 13, 23 (21, 31, 32 accepted)");
  const int i = label[0] - '1', j = label[1] - '1';
  if (c.mode == TestMode::uniaxial) {
    if (i != j)
      throw core::UsageError("model fritzson: a uniaxial test needs orientation 11, 22 or 33, not '" +
                             label + "'");
    o.uniaxial_axis = i;
  } else {
    if (i == j)
      throw core::UsageError("model fritzson: a shear test needs orientation 12, 13 or 23, not '" +
                             label + "'");
    o.fibre_shear = (i == 2 || j == 2);
  }
  if (!anisotropic) o = Orientation{};
  return o;
}

template <typename T>
T complex_abs(const std::complex<T>& z) {
  return safe_sqrt(z.real() * z.real() + z.imag() * z.imag());
}

// Uniaxial stress along `axis`. With M_I the isotropic and M_A the A1 modulus, the deviatoric
// stiffness on normal strains is 2M_I m̂m̂ᵀ + 2(M_I + M_A) n̂n̂ᵀ (m̂ = (1,−1,0)/√2,
// n̂ = (−½,−½,1)/√1.5) and the volumetric one K 11ᵀ act on orthogonal subspaces, so the
// compliance is S = 11ᵀ/(9K) + m̂m̂ᵀ/(2M_I) + n̂n̂ᵀ/(2(M_I + M_A)): no cancellation for any K/G.
template <typename T, typename M>
struct UniaxialSolution {
  M modulus;      // σ_axis / ε_axis
  M deviatoric[3];  // deviatoric normal strains per unit ε_axis
};

template <typename T, typename M>
UniaxialSolution<T, M> uniaxial(const T& K, const M& M_I, const M& M_A, int axis) {
  static const double m_hat[3] = {0.70710678118654752, -0.70710678118654752, 0.0};
  static const double n_hat[3] = {-0.40824829046386302, -0.40824829046386302, 0.81649658092772603};
  const M cm = T(m_hat[axis]) / (T(2.0) * M_I);
  const M cn = T(n_hat[axis]) / (T(2.0) * (M_I + M_A));
  const M compliance = M(T(1.0) / (9.0 * K)) + T(m_hat[axis]) * cm + T(n_hat[axis]) * cn;
  UniaxialSolution<T, M> out;
  out.modulus = M(T(1.0)) / compliance;
  for (int k = 0; k < 3; ++k)
    out.deviatoric[k] = (T(m_hat[k]) * cm + T(n_hat[k]) * cn) / compliance;
  return out;
}

class FritzsonModel final : public AutodiffModel<FritzsonModel> {
 public:
  FritzsonModel(bool anisotropic, double reference_C)
      : anisotropic_(anisotropic), reference_C_(reference_C), specs_(parameter_specs(anisotropic)) {}

  std::string kind() const override { return anisotropic_ ? "fritzson" : "fritzson-iso"; }
  bool anisotropic() const { return anisotropic_; }
  double reference_C() const { return reference_C_; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  nlohmann::json options() const override { return {{"reference_C", reference_C_}}; }
  // Describes shear, uniaxial (all orientations) and bulk alike; shear is its natural card.
  TestMode native_mode() const override { return TestMode::shear; }
  bool amplitude_dependent() const override { return true; }
  // The drivers the moduli of a test read (evaluate): shear γ/√2 for I, and for A2 in 13/23; uniaxial
  // the fixed point of the damaged lateral strains (A2 reads the fibre strain as A1 does, 4.78).
  std::vector<double> damage_drivers(const double* p, const TestCondition& c) const override {
    std::array<double, 3> d{{0.0, 0.0, 0.0}};
    const Orientation o = checked_orientation(c);
    if (c.mode == TestMode::shear) {
      d[0] = shear_driver(c), d[2] = o.fibre_shear ? shear_driver(c) : 0.0;
    } else if (c.mode == TestMode::uniaxial) {
      solve_drivers(p, c, o.uniaxial_axis, d[0], d[1]);
      d[2] = d[1];
    }
    return anisotropic_ ? std::vector<double>(d.begin(), d.end()) : std::vector<double>{d[0]};
  }
  double bulk_modulus(const double* p) const override { return p[kK]; }
  TemperatureLawInfo temperature_law_info() const override {
    TemperatureLawInfo info;  // no horizontal shift; reversible linear factors per part
    info.reference_C = reference_C_;
    info.linear_factor = true;
    return info;
  }
  // The factor with the lowest g names the reason (the tightest limit of those that fail).
  std::string temperature_out_of_law(const double* p, double temperature_C) const override {
    int lowest = -1;
    for (int part : {kPartI, kPartA1, kPartA2}) {
      if (part != kPartI && !anisotropic_) break;
      for (int k : {part + kC1, part + kC2})
        if (lowest < 0 || p[k] * (temperature_C - reference_C_) > p[lowest] * (temperature_C - reference_C_))
          lowest = k;
    }
    return linear_factor_out_of_law(specs_[lowest].name, p[lowest], reference_C_, temperature_C, kTemperatureFloor);
  }
  std::shared_ptr<const model::MaterialPoint> material_point(
      const double* p, const PointOptions& options) const override {
    return make_contract_point(std::vector<double>(p, p + size()), anisotropic_, reference_C_,
                               options);
  }
  nlohmann::json temperature_law(const double* p) const override {
    nlohmann::json law = {{"law", "linear-factors"}, {"reference_C", reference_C_},
                          {"c1_I", p[kPartI + kC1]}, {"c2_I", p[kPartI + kC2]}};
    if (anisotropic_)
      for (const auto& [name, index] : {std::pair<const char*, int>{"c1_A1", kPartA1 + kC1},
                                        {"c2_A1", kPartA1 + kC2}, {"c1_A2", kPartA2 + kC1},
                                        {"c2_A2", kPartA2 + kC2}})
        law[name] = p[index];
    return law;
  }

  template <typename T>
  Moduli<T> evaluate(const T* p, const TestCondition& c) const {
    const Orientation o = checked_orientation(c);
    const double omega = 2.0 * kPi * c.frequency_Hz;
    const double amplitude = c.strain_amplitude;
    const T& K = p[kK];
    if (c.mode == TestMode::bulk) return {K, T(0.0), K};  // purely elastic (4.39; docs/fritzson.md §1)

    if (c.mode == TestMode::shear) {
      PartModuli<T> m = part(p + kPartI, shear_driver(c), omega, c);
      if (o.fibre_shear) {
        const PartModuli<T> a2 = part(p + kPartA2, shear_driver(c), omega, c);
        m.dynamic += a2.dynamic;
        m.mean += a2.mean;
      }
      return {m.dynamic.real(), m.dynamic.imag(), m.mean};
    }

    // Uniaxial: the damage drivers depend on the lateral strains, which depend on the damaged
    // moduli: solve for the fixed point (the thesis iterated; docs/fritzson.md §3). Doubles: Newton. Other
    // scalars (only the generic AutodiffModel passes use them): plain iteration, which carries
    // the derivatives along.
    T driver_I, driver_A;
    if constexpr (std::is_same_v<T, double>) {
      solve_drivers(p, c, o.uniaxial_axis, driver_I, driver_A);
    } else {
      uniaxial_start(amplitude, driver_I, driver_A);
      for (int iteration = 0; iteration < kMaxFixedPointIterations; ++iteration) {
        const UniaxialStep<T> next =
            uniaxial_step(p, c, o.uniaxial_axis, driver_I, driver_A, false);
        const bool done = converged(driver_I, driver_A, next, amplitude) && iteration > 0;
        driver_I = next.driver_I;
        driver_A = next.driver_A;
        if (done) break;
      }
    }
    return uniaxial_step(p, c, o.uniaxial_axis, driver_I, driver_A, true).moduli;
  }

  using AutodiffModel<FritzsonModel>::moduli;

  // Jacobian by forward-mode passes over only the parameters the test depends on (shear 12:
  // part I; 13/23: I and A2, one pass each; uniaxial: K, I and A1; bulk: K), instead of the
  // generic passes of 8 over all 38 (most columns of a row are zero). Uniaxial: the damage
  // drivers d solve d = F(d, p) (found in doubles); the implicit function theorem gives
  // dd/dp = (1 − ∂F/∂d)⁻¹ ∂F/∂p from one pass that also seeds d, so no iteration runs on jets.
  Moduli<double> moduli(const double* p, const TestCondition& c,
                        Eigen::Ref<Eigen::MatrixXd> jacobian) const override {
    jacobian.setZero();
    const Orientation o = checked_orientation(c);
    if (c.mode == TestMode::bulk) {
      jacobian(0, kK) = jacobian(2, kK) = 1.0;
      return evaluate<double>(p, c);
    }
    if (c.mode == TestMode::shear) {  // the parts add: one pass of 12 per part
      Moduli<double> m = shear_part_pass(p, c, kPartI, jacobian);
      if (o.fibre_shear) {
        const Moduli<double> a2 = shear_part_pass(p, c, kPartA2, jacobian);
        m = {m.storage + a2.storage, m.loss + a2.loss, m.mean + a2.mean};
      }
      return m;
    }
    if (anisotropic_)
      return uniaxial_pass<2 * kPartSize + 3>(p, c, o, {kPartI, kPartA1}, jacobian);
    return uniaxial_pass<kPartSize + 3>(p, c, o, {kPartI}, jacobian);
  }

  std::vector<double> stress_response(const double* p, const TestCondition& c,
                                      const StrainHistory& history) const override {
    const MaterialPoint point(std::vector<double>(p, p + size()), anisotropic_, reference_C_,
                              Scheme::exponential);
    return drive_test(point, c, history).stress;
  }

  // Shear and bulk: a strain step leaves the running mean equal to the strain (e^o = 0), so no
  // dynamic stress and no damage arise and the model is linear: closed form. Uniaxial: the lateral
  // strains creep, so it is integrated numerically with a fine log grid.
  double relaxation_modulus(const double* p, const TestCondition& c, double t_s) const override {
    if (c.mode == TestMode::bulk) return p[kK];
    const Orientation o = parse_orientation(c, anisotropic_);
    auto relax = [&](const double* part) {
      const double g1 = temperature_factor(part[kC1], c.temperature_C, reference_C_);
      const double g2 = temperature_factor(part[kC2], c.temperature_C, reference_C_);
      double times[5];
      maxwell_times(part[kTau], part[kK_ratio], times);
      double sum = 0.0;
      for (double tau : times) sum += std::exp(-t_s / tau);
      return g1 * part[kMean] + g2 * part[kBeta2] * part[kViscous] * sum;  // h1 = 1, h2 = β2
    };
    if (c.mode == TestMode::shear)
      return relax(p + kPartI) + (o.fibre_shear ? relax(p + kPartA2) : 0.0);
    const double strain = 1e-6;  // small: the lateral creep is what matters, damage stays at 0
    StrainHistory h;
    h.time_s.push_back(0.0);
    h.strain.push_back(strain);
    if (t_s > 0.0) {
      const double t_first = std::min(t_s, 1e-9);
      const int n = 400;
      for (int k = 0; k <= n; ++k) {
        h.time_s.push_back(t_first * std::pow(t_s / t_first, double(k) / n));
        h.strain.push_back(strain);
      }
    }
    return stress_response(p, c, h).back() / strain;
  }

  double creep_compliance(const double*, const TestCondition&, double) const override {
    throw core::UsageError(
        "model fritzson: creep compliance is not provided: under a stress step the strain moves "
        "away from its running mean, so the rate-independent dynamic part and the amplitude damage "
        "make the response path dependent; integrate the stress history with a mixed-control "
        "driver (fritzson::drive_test) instead");
  }

  std::vector<double> initial_parameters(const DataSummary& data) const override {
    std::vector<double> p = default_parameters();
    // Loss peak in the middle of the measured frequencies; moduli from the storage level.
    const double tau = 1.0 / std::sqrt(data.omega_min_rad_s * data.omega_max_rad_s);
    const double storage = std::sqrt(data.storage_min_MPa * data.storage_max_MPa);
    const double shear_scale = std::max(storage / 3.0, 1e-3);  // data may be uniaxial
    p[kPartI + kTau] = tau;
    p[kPartI + kMean] = 0.5 * shear_scale;
    p[kPartI + kDynamic] = 0.3 * shear_scale;
    p[kPartI + kViscous] = std::max(0.2 * shear_scale, data.loss_max_MPa / 2.0);
    p[kK] = 1e3 * shear_scale;
    if (anisotropic_) {
      p[kPartA1 + kTau] = tau;
      p[kPartA2 + kTau] = tau;
    }
    return p;
  }

 private:
  static constexpr int kMaxFixedPointIterations = 100;

  // Moduli at given uniaxial damage drivers, and the drivers they imply (the fixed-point map).
  template <typename T>
  struct UniaxialStep {
    Moduli<T> moduli;  // mean modulus only when asked for
    T driver_I, driver_A;
  };

  // Incompressible start of the uniaxial drivers.
  template <typename T>
  static void uniaxial_start(double amplitude, T& driver_I, T& driver_A) {
    driver_I = T(std::sqrt(1.5) * amplitude);
    driver_A = T(std::sqrt(2.0) * amplitude);
  }

  template <typename T>
  static bool converged(const T& driver_I, const T& driver_A, const UniaxialStep<T>& next,
                        double amplitude) {
    const double change = std::abs(scalar_part(next.driver_I) - scalar_part(driver_I)) +
                          std::abs(scalar_part(next.driver_A) - scalar_part(driver_A));
    return change <= 1e-14 * (amplitude + 1e-300);
  }

  template <typename T>
  UniaxialStep<T> uniaxial_step(const T* p, const TestCondition& c, int axis, const T& driver_I,
                                const T& driver_A, bool with_mean) const {
    using C = std::complex<T>;
    const double omega = 2.0 * kPi * c.frequency_Hz;
    const double amplitude = c.strain_amplitude;
    const PartModuli<T> mi = part(p + kPartI, driver_I, omega, c);
    PartModuli<T> ma{C(T(0.0), T(0.0)), T(0.0)};
    if (anisotropic_) ma = part(p + kPartA1, driver_A, omega, c);
    const UniaxialSolution<T, C> steady = uniaxial<T, C>(p[kK], mi.dynamic, ma.dynamic, axis);
    // Peak over a cycle of |Re(ê e^{iωt})|: √(½(Σ|ê_k|² + |Σ ê_k²|)) (tensor norm, 4.32).
    T sum_abs2(0.0);
    C sum_sq(T(0.0), T(0.0));
    for (const C& e : steady.deviatoric) {
      const C ea = e * T(amplitude);
      sum_abs2 += ea.real() * ea.real() + ea.imag() * ea.imag();
      sum_sq += ea * ea;
    }
    UniaxialStep<T> out;
    out.driver_I = safe_sqrt(0.5 * (sum_abs2 + complex_abs(sum_sq)));
    out.driver_A = std::sqrt(2.0) * complex_abs(steady.deviatoric[2] * T(amplitude));
    out.moduli.storage = steady.modulus.real();
    out.moduli.loss = steady.modulus.imag();
    out.moduli.mean =
        with_mean ? uniaxial<T, T>(p[kK], mi.mean, ma.mean, axis).modulus : T(0.0);
    return out;
  }

  Orientation checked_orientation(const TestCondition& c) const {
    if (!(c.frequency_Hz > 0.0) || !std::isfinite(c.frequency_Hz))
      throw core::UsageError("model fritzson: the frequency must be positive and finite");
    if (!(c.strain_amplitude >= 0.0) || !std::isfinite(c.strain_amplitude))
      throw core::UsageError("model fritzson: the strain amplitude must be ≥ 0 and finite");
    return parse_orientation(c, anisotropic_);
  }

  // Uniaxial damage drivers at the fixed point d = F(d): Newton's method on F(d) − d with the
  // 2 × 2 Jacobian from a two-slot jet (3–4 steps where plain iteration takes ~20); a plain
  // step wherever Newton's would leave d ≥ 0 or is not finite.
  void solve_drivers(const double* p, const TestCondition& c, int axis, double& d_I,
                     double& d_A) const {
    using Jet2 = ceres::Jet<double, 2>;
    const int n = static_cast<int>(size());
    std::vector<Jet2> pj(n);
    for (int i = 0; i < n; ++i) pj[i] = Jet2(p[i]);
    const double amplitude = c.strain_amplitude;
    uniaxial_start(amplitude, d_I, d_A);
    for (int iteration = 0; iteration < kMaxFixedPointIterations; ++iteration) {
      const UniaxialStep<Jet2> f =
          uniaxial_step(pj.data(), c, axis, Jet2(d_I, 0), Jet2(d_A, 1), false);
      const double r_I = f.driver_I.a - d_I, r_A = f.driver_A.a - d_A;
      const double a11 = f.driver_I.v[0] - 1.0, a12 = f.driver_I.v[1];
      const double a21 = f.driver_A.v[0], a22 = f.driver_A.v[1] - 1.0;
      const double det = a11 * a22 - a12 * a21;
      double step_I = -(a22 * r_I - a12 * r_A) / det, step_A = -(a11 * r_A - a21 * r_I) / det;
      if (!std::isfinite(step_I) || !std::isfinite(step_A) || d_I + step_I < 0.0 ||
          d_A + step_A < 0.0) {
        step_I = r_I;
        step_A = r_A;
      }
      d_I += step_I;
      d_A += step_A;
      if (std::abs(step_I) + std::abs(step_A) <= 1e-14 * (amplitude + 1e-300)) break;
    }
  }

  // Steady shear driver e^o = γ_a/√2 of I and, in 13/23, of A2 (4.32, 4.78).
  static double shear_driver(const TestCondition& c) { return c.strain_amplitude / std::sqrt(2.0); }

  // Shear moduli of one part and their derivatives (columns offset … offset + 11).
  Moduli<double> shear_part_pass(const double* p, const TestCondition& c, int offset,
                                 Eigen::Ref<Eigen::MatrixXd> jacobian) const {
    using Jet = ceres::Jet<double, kPartSize>;
    Jet q[kPartSize];
    for (int k = 0; k < kPartSize; ++k) q[k] = Jet(p[offset + k], k);
    const PartModuli<Jet> m = part(q, shear_driver(c), 2.0 * kPi * c.frequency_Hz, c);
    for (int k = 0; k < kPartSize; ++k) {
      jacobian(0, offset + k) = m.dynamic.real().v[k];
      jacobian(1, offset + k) = m.dynamic.imag().v[k];
      jacobian(2, offset + k) = m.mean.v[k];
    }
    return {m.dynamic.real().a, m.dynamic.imag().a, m.mean.a};
  }

  // Uniaxial moduli and derivatives in one forward-mode pass with N slots: K and the parts at
  // `part_offsets` take the first, the two damage drivers the last two.
  template <int N>
  Moduli<double> uniaxial_pass(const double* p, const TestCondition& c, const Orientation& o,
                               std::initializer_list<int> part_offsets,
                               Eigen::Ref<Eigen::MatrixXd> jacobian) const {
    using Jet = ceres::Jet<double, N>;
    const int n = static_cast<int>(size());
    std::vector<Jet> pj(n);
    for (int i = 0; i < n; ++i) pj[i] = Jet(p[i]);
    int columns[N];
    int slots = 0;
    auto seed = [&](int i) {
      pj[i].v[slots] = 1.0;
      columns[slots++] = i;
    };
    seed(kK);
    for (int offset : part_offsets)
      for (int k = 0; k < kPartSize; ++k) seed(offset + k);
    // Drivers at the fixed point (doubles), then one pass seeding them too.
    double d_I, d_A;
    solve_drivers(p, c, o.uniaxial_axis, d_I, d_A);
    const int sI = N - 2, sA = N - 1;
    Jet driver_I(d_I), driver_A(d_A);
    driver_I.v[sI] = 1.0;
    driver_A.v[sA] = 1.0;
    const UniaxialStep<Jet> step = uniaxial_step(pj.data(), c, o.uniaxial_axis, driver_I,
                                                 driver_A, true);
    // (1 − ∂F/∂d) dd/dp = ∂F/∂p, a 2 × 2 system.
    const double a11 = 1.0 - step.driver_I.v[sI], a12 = -step.driver_I.v[sA];
    const double a21 = -step.driver_A.v[sI], a22 = 1.0 - step.driver_A.v[sA];
    const double det = a11 * a22 - a12 * a21;
    const Jet* out[3] = {&step.moduli.storage, &step.moduli.loss, &step.moduli.mean};
    for (int s = 0; s < slots; ++s) {
      const double fI = step.driver_I.v[s], fA = step.driver_A.v[s];
      const double dI = (a22 * fI - a12 * fA) / det, dA = (a11 * fA - a21 * fI) / det;
      for (int r = 0; r < 3; ++r)
        jacobian(r, columns[s]) = out[r]->v[s] + out[r]->v[sI] * dI + out[r]->v[sA] * dA;
    }
    return {step.moduli.storage.a, step.moduli.loss.a, step.moduli.mean.a};
  }

  template <typename T, typename D>
  PartModuli<T> part(const T* part_p, const D& driver, double omega, const TestCondition& c) const {
    const PartFactors<T> f = part_factors(part_p, driver, c.temperature_C, reference_C_);
    return part_moduli(part_p, f, omega);
  }

  bool anisotropic_;
  double reference_C_;
  std::vector<ParameterSpec> specs_;
};

}  // namespace

std::vector<core::ParameterSpec> parameter_specs(bool anisotropic) {
  std::vector<ParameterSpec> specs;
  specs.push_back({"K", "MPa", 1.0, 1e7, Transform::log, "volumetric", 2000.0, true});
  add_part(specs, "I", "G", true, 2.0, 1.0, 1.0);
  specs.push_back({"C_d", "-", 1e-3, 1e4, Transform::log, "damage", 0.6, false});
  if (anisotropic) {
    add_part(specs, "A1", "C33", false, 4.0, 2.0, 1.0);
    add_part(specs, "A2", "C44", false, 1.0, 0.5, 0.3);
  }
  // Linear in the moduli only for shear tests: uniaxial tests combine K, G and C' non-linearly
  // (E = 9KM/(3K + M), E22 = 12G(G+C')/(4G+3C') when incompressible), so no flag is set.
  for (auto& s : specs) s.linear = false;
  return specs;
}

bool is_fritzson_kind(const std::string& kind) {
  return kind == "fritzson" || kind == "fritzson-iso";
}

ModelPtr make_fritzson_model(const std::string& kind, const nlohmann::json& options) {
  if (!is_fritzson_kind(kind))
    throw core::UsageError("make_fritzson_model: unknown kind '" + kind + "'");
  double reference_C = 23.0;
  if (!options.is_null()) {
    if (!options.is_object())
      throw core::UsageError("model " + kind + ": options must be a JSON object");
    for (const auto& [key, value] : options.items()) {
      if (key == "reference_C" && value.is_number()) {
        reference_C = value.get<double>();
      } else if (key == "mode" && value.is_string()) {
        parse_test_mode(value.get<std::string>());  // the model answers every mode
      } else if (key == "bulk_modulus" && value.is_boolean()) {
        // K is always part of the model.
      } else if (key == "temperature_law" && value.is_string()) {
        const std::string law = value.get<std::string>();
        if (law != "none" && law != "linear" && law != "linear-factors")
          throw core::UsageError("model " + kind + ": temperature law '" + law +
                                 "' is not available; the model has its own linear factors "
                                 "g = 1 - c (T - T_ref) (use none or linear)");
      } else {
        throw core::UsageError("model " + kind + ": unknown option '" + key +
                               "' (known: reference_C in degC; mode, bulk_modulus and "
                               "temperature_law none|linear are accepted and built in)");
      }
    }
  }
  return std::make_shared<FritzsonModel>(kind == "fritzson", reference_C);
}

MaterialPoint thesis_point(const Model& model, const std::vector<double>& p) {
  const auto* m = dynamic_cast<const FritzsonModel*>(&model);
  if (!m) throw core::UsageError("the thesis cases need a fritzson card, not '" + model.kind() + "'");
  return MaterialPoint(p, m->anisotropic(), m->reference_C(), Scheme::exponential);
}

}  // namespace fitlib::model::fritzson
