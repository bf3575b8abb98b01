// Hyperelastic laws as models (model/hyperelastic.hpp, docs/hyperelastic.md).
#include "fitlib/model/hyperelastic.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/autodiff_model.hpp"
#include "fitlib/model/material_point.hpp"
#include "hyperelastic_laws.hpp"

namespace fitlib::model {

MaterialPointPtr hyperelastic_point(std::shared_ptr<const Model> model, std::vector<double> values,
                                    const PointOptions& options);  // hyperelastic_point.cpp

namespace {

using core::ParameterSpec;
using core::Transform;
using hyper::Structure;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxTerms = 6;
using Jet = ceres::Jet<double, 2 * kMaxTerms + 1>;

ParameterSpec coefficient(const std::string& name, double start) {
  return {name, "MPa", -kInf, kInf, Transform::linear, "hyperelastic", start, true};
}

struct Kind {
  const char* name;
  HyperelasticFamily family;
  int default_terms, min_terms, max_terms;  // terms option (0 = none)
};
constexpr Kind kKinds[] = {
    {"neo-hooke", HyperelasticFamily::neo_hooke, 0, 0, 0},
    {"mooney-rivlin", HyperelasticFamily::mooney_rivlin, 2, 2, 3},
    {"yeoh", HyperelasticFamily::yeoh, 0, 0, 0},
    {"reduced-polynomial", HyperelasticFamily::reduced_polynomial, 3, 1, kMaxTerms},
    {"ogden", HyperelasticFamily::ogden, 3, 1, kMaxTerms},
    {"arruda-boyce", HyperelasticFamily::arruda_boyce, 0, 0, 0},
    {"gent", HyperelasticFamily::gent, 0, 0, 0},
};

const Kind* find_kind(const std::string& name) {
  for (const auto& k : kKinds)
    if (name == k.name) return &k;
  return nullptr;
}

// Parameters and exponents of a kind with `terms` terms.
void declare(const Kind& kind, int terms, Structure& s, std::vector<ParameterSpec>& specs) {
  s.family = kind.family;
  const auto poly = [&](int i, int j, double start) {
    s.exponents.emplace_back(i, j);
    specs.push_back(coefficient("C" + std::to_string(i) + std::to_string(j), start));
  };
  switch (kind.family) {
    case HyperelasticFamily::neo_hooke: poly(1, 0, 0.2); break;
    case HyperelasticFamily::mooney_rivlin:
      poly(1, 0, 0.2), poly(0, 1, 0.01);
      if (terms == 3) poly(1, 1, 0.0);
      break;
    case HyperelasticFamily::yeoh: terms = 3; [[fallthrough]];
    case HyperelasticFamily::reduced_polynomial:
      for (int i = 1; i <= terms; ++i) poly(i, 0, i == 1 ? 0.2 : 0.0);
      break;
    case HyperelasticFamily::ogden:
      s.ogden_terms = terms;
      for (int k = 1; k <= terms; ++k) {
        const double alpha = k == 1 ? 1.3 : k == 2 ? 5.0 : k == 3 ? -2.0 : 2.0 * k;
        specs.push_back(coefficient("mu_" + std::to_string(k), k == 1 ? 0.4 : 0.001));
        specs.push_back({"alpha_" + std::to_string(k), "-", -50.0, 50.0, Transform::linear, "hyperelastic", alpha, false});
      }
      break;
    case HyperelasticFamily::arruda_boyce:
      specs.push_back({"mu", "MPa", 0.0, kInf, Transform::log, "hyperelastic", 0.3, true});
      specs.push_back({"lambda_m", "-", 1.0, kInf, Transform::linear, "hyperelastic", 5.0, false});
      break;
    case HyperelasticFamily::gent:
      specs.push_back({"mu", "MPa", 0.0, kInf, Transform::log, "hyperelastic", 0.3, true});
      specs.push_back({"J_m", "-", 0.0, kInf, Transform::log, "hyperelastic", 100.0, false});
      break;
  }
}

class HyperelasticModel final : public AutodiffModel<HyperelasticModel>,
                                public HyperelasticLaw,
                                public std::enable_shared_from_this<HyperelasticModel> {
 public:
  HyperelasticModel(const Kind& kind, int terms, bool compressible) : kind_(kind), terms_(terms) {
    declare(kind, terms, s_, specs_);
    s_.compressible = compressible;
    if (compressible) specs_.push_back({"D1", "1/MPa", 0.0, kInf, Transform::log, "volumetric", 1e-3, false});
  }

  std::string kind() const override { return kind_.name; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  nlohmann::json options() const override {
    nlohmann::json o = {{"compressible", s_.compressible}};
    if (kind_.max_terms > 0) o["terms"] = terms_;
    return o;
  }
  TestMode native_mode() const override { return TestMode::shear; }
  const HyperelasticLaw* hyperelastic() const override { return this; }
  double bulk_modulus(const double* p) const override {
    return s_.compressible ? 2.0 / p[s_.d1_index()] : std::nan("");
  }

  // Small-strain moduli: G = μ0, E = 3 μ0 (incompressible) or 9 K G/(3K + G), K = 2/D1.
  template <typename T>
  Moduli<T> evaluate(const T* p, const TestCondition& c) const {
    const T G = shear_modulus(p);
    T m = G;
    if (c.mode == TestMode::uniaxial)
      m = s_.compressible ? T(9.0) * (2.0 / p[s_.d1_index()]) * G / (T(3.0) * (2.0 / p[s_.d1_index()]) + G) : T(3.0) * G;
    if (c.mode == TestMode::bulk) {
      if (!s_.compressible) throw core::UsageError(kind() + ": an incompressible law has no bulk modulus");
      m = 2.0 / p[s_.d1_index()];
    }
    return {m, T(0.0), m};
  }

  // Rate-independent: the nominal stress of the mode at each strain (shear: simple shear at γ;
  // uniaxial: stretch 1 + ε; bulk: pressure at J = 1 + θ, as a mean stress).
  std::vector<double> stress_response(const double* p, const TestCondition& c, const StrainHistory& h) const override {
    check_strain_history(h);
    std::vector<double> out;
    for (double e : h.strain) {
      if (c.mode == TestMode::shear) out.push_back(nominal_stress(p, DeformationMode::simple_shear, e));
      else if (c.mode == TestMode::uniaxial) out.push_back(nominal_stress(p, DeformationMode::uniaxial, 1.0 + e));
      else out.push_back(-nominal_stress(p, DeformationMode::volumetric, 1.0 + e));
    }
    return out;
  }
  double relaxation_modulus(const double* p, const TestCondition& c, double) const override {
    return moduli(p, c).storage;
  }
  double creep_compliance(const double* p, const TestCondition& c, double) const override {
    return 1.0 / moduli(p, c).storage;
  }
  std::shared_ptr<const MaterialPoint> material_point(const double* p, const PointOptions& options) const override {
    return hyperelastic_point(shared_from_this(), std::vector<double>(p, p + size()), options);
  }

  // ---- HyperelasticLaw
  bool compressible() const override { return s_.compressible; }

  double nominal_stress(const double* p, DeformationMode mode, double x, double* gradient = nullptr) const override {
    require_mode(mode, x);
    const int n = static_cast<int>(size());
    if (!gradient) return hyper::nominal_stress<double>(s_, p, mode, x);
    std::vector<Jet> pj(n);
    for (int i = 0; i < n; ++i) pj[i] = Jet(p[i], i);
    const Jet P = hyper::nominal_stress<Jet>(s_, pj.data(), mode, x);
    for (int i = 0; i < n; ++i) gradient[i] = P.v[i];
    return P.a;
  }

  double energy(const double* p, const std::array<double, 3>& l) const override {
    const double J = l[0] * l[1] * l[2];
    const double f = std::cbrt(J);
    const double bar[3] = {l[0] / f, l[1] / f, l[2] / f};
    double W = hyper::isochoric_energy<double>(s_, p, bar);
    if (s_.compressible) W += hyper::volumetric_energy<double>(s_, p, J);
    return W;
  }

  // τ_i = dev(τ̄)_i + J U'(J) (the isochoric part is deviatoric: Ogden 1984, §4.4).
  std::array<double, 3> principal_kirchhoff(const double* p, const std::array<double, 3>& l,
                                            double bulk_modulus_MPa) const override {
    const double J = l[0] * l[1] * l[2];
    const double f = std::cbrt(J);
    const double bar[3] = {l[0] / f, l[1] / f, l[2] / f};
    double t[3];
    hyper::tau<double>(s_, p, bar, t);
    const double mean = (t[0] + t[1] + t[2]) / 3.0;
    const double vol = s_.compressible ? J * hyper::volumetric_slope<double>(s_, p, J)
                                       : J * bulk_modulus_MPa * (J - 1.0);  // U = K (J − 1)²/2
    return {t[0] - mean + vol, t[1] - mean + vol, t[2] - mean + vol};
  }

  std::array<double, 3> drucker_tangent(const double* p, double lambda1, double lambda2) const override {
    using J2 = ceres::Jet<double, 2>;
    std::vector<J2> pj(p, p + size());
    const J2 e1(std::log(lambda1), 0), e2(std::log(lambda2), 1);
    const J2 lam[3] = {exp(e1), exp(e2), exp(-e1 - e2)};
    J2 t[3];
    hyper::tau<J2>(s_, pj.data(), lam, t);
    // ∂W/∂ε_i = τ_i − τ_3 (σ3 = 0); its Jacobian is the Hessian (D11, D12, D22).
    const J2 s1 = t[0] - t[2], s2 = t[1] - t[2];
    return {s1.v[0], 0.5 * (s1.v[1] + s2.v[0]), s2.v[1]};
  }

  double initial_shear_modulus(const double* p) const override { return shear_modulus(p); }

  HyperelasticForm form(const double* p) const override {
    HyperelasticForm f;
    f.family = s_.family;
    f.order = terms_ > 0 ? terms_ : s_.family == HyperelasticFamily::yeoh ? 3 : 1;
    if (s_.family == HyperelasticFamily::mooney_rivlin) f.order = terms_ == 3 ? 2 : 1;
    for (std::size_t k = 0; k < s_.exponents.size(); ++k)
      f.coefficients.push_back({s_.exponents[k].first, s_.exponents[k].second, p[k]});
    for (int k = 0; k < s_.ogden_terms; ++k) f.mu_MPa.push_back(p[2 * k]), f.alpha.push_back(p[2 * k + 1]);
    if (s_.family == HyperelasticFamily::arruda_boyce) f.mu_MPa = {p[0]}, f.lambda_m = p[1];
    if (s_.family == HyperelasticFamily::gent) f.mu_MPa = {p[0]}, f.J_m = p[1];
    if (s_.compressible) f.D1_per_MPa = p[s_.d1_index()];
    f.initial_shear_modulus_MPa = shear_modulus(p);
    return f;
  }

  std::string outside_domain(const double* p, DeformationMode mode, double x) const override {
    if (s_.family != HyperelasticFamily::gent || mode == DeformationMode::volumetric) return {};
    const std::array<double, 3> l = principal_stretches(mode, x);
    const double I1 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    if (I1 - 3.0 < p[1]) return {};
    return std::string("gent: ") + to_string(mode) + " " + abscissa_name(mode) + " " + core::format_number(x) +
           " is at or beyond the locking stretch (I1 - 3 >= J_m = " + core::format_number(p[1]) + ")";
  }

 private:
  static std::array<double, 3> principal_stretches(DeformationMode mode, double x) {
    switch (mode) {
      case DeformationMode::uniaxial: return {x, 1.0 / std::sqrt(x), 1.0 / std::sqrt(x)};
      case DeformationMode::equibiaxial: return {x, x, 1.0 / (x * x)};
      case DeformationMode::planar: return {x, 1.0, 1.0 / x};
      case DeformationMode::simple_shear: {
        const double l1 = 0.5 * x + std::sqrt(1.0 + 0.25 * x * x);
        return {l1, 1.0 / l1, 1.0};
      }
      case DeformationMode::volumetric: break;
    }
    const double f = std::cbrt(x);
    return {f, f, f};
  }

  void require_mode(DeformationMode mode, double x) const {
    if (mode == DeformationMode::volumetric && !s_.compressible)
      throw core::UsageError(kind() + ": an incompressible law has no volumetric response (option compressible)");
    if (mode != DeformationMode::simple_shear && !(x > 0.0))
      throw core::UsageError(kind() + ": the " + abscissa_name(mode) + " must be > 0");
  }

  // μ0: 2 (C10 + C01) (polynomial families), Σ μ_i (Ogden), μ (1 + 3/(5 λm²) + …) (Arruda–Boyce),
  // μ (Gent).
  template <typename T>
  T shear_modulus(const T* p) const {
    switch (s_.family) {
      case HyperelasticFamily::ogden: {
        T g(0.0);
        for (int k = 0; k < s_.ogden_terms; ++k) g += p[2 * k];
        return g;
      }
      case HyperelasticFamily::arruda_boyce: {
        T W1, W2;  // μ0 = 2 ∂W/∂I1 at I1 = 3
        hyper::invariant_derivatives(s_, p, T(3.0), T(3.0), W1, W2);
        return 2.0 * W1;
      }
      case HyperelasticFamily::gent: return p[0];
      default: {
        T g(0.0);
        for (std::size_t k = 0; k < s_.exponents.size(); ++k)
          if (s_.exponents[k].first + s_.exponents[k].second == 1) g += 2.0 * p[k];
        return g;
      }
    }
  }

  const Kind& kind_;
  int terms_;
  Structure s_;
  std::vector<ParameterSpec> specs_;
};

}  // namespace

double HyperelasticLaw::cauchy_stress(const double* p, DeformationMode mode, double x) const {
  const double P = nominal_stress(p, mode, x);
  return (mode == DeformationMode::simple_shear || mode == DeformationMode::volumetric) ? P : P * x;
}

bool is_hyperelastic_kind(const std::string& kind) { return find_kind(kind) != nullptr; }

const std::vector<std::string>& hyperelastic_kinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> k;
    for (const auto& kind : kKinds) k.push_back(kind.name);
    return k;
  }();
  return kinds;
}

ModelPtr make_hyperelastic_model(const std::string& name, const nlohmann::json& options) {
  const Kind* kind = find_kind(name);
  if (!kind) throw core::UsageError("not a hyperelastic model kind: '" + name + "'");
  const nlohmann::json o = options.is_null() ? nlohmann::json::object() : options;
  if (!o.is_object()) throw core::UsageError(name + ": model options must be an object");
  int terms = kind->default_terms;
  bool compressible = false;
  for (const auto& [key, value] : o.items()) {
    if (key == "terms" && kind->max_terms > 0) {
      if (!value.is_number_integer() || value.get<int>() < kind->min_terms || value.get<int>() > kind->max_terms)
        throw core::UsageError(name + ": option terms must be an integer in " + std::to_string(kind->min_terms) + ".." +
                               std::to_string(kind->max_terms));
      terms = value.get<int>();
    } else if (key == "compressible") {
      if (!value.is_boolean()) throw core::UsageError(name + ": option compressible must be true or false");
      compressible = value.get<bool>();
    } else {
      throw core::UsageError(name + ": unknown model option '" + key + "' (" +
                             (kind->max_terms > 0 ? "terms, compressible" : "compressible") + ")");
    }
  }
  return std::make_shared<HyperelasticModel>(*kind, terms, compressible);
}

// Log-spaced from 1 to `stretch`: the Hessian's leading minor and determinant must stay > 0.
double first_unstable_stretch(const HyperelasticLaw& law, const double* p, DeformationMode mode, double stretch,
                              int steps) {
  for (int k = 1; k <= steps; ++k) {
    const double x = std::exp(std::log(stretch) * k / steps);
    double l1 = x, l2 = 1.0;
    if (mode == DeformationMode::uniaxial) l2 = 1.0 / std::sqrt(x);
    else if (mode == DeformationMode::equibiaxial) l2 = x;
    else if (mode != DeformationMode::planar) throw core::UsageError("Drucker check: uniaxial, equibiaxial or planar");
    if (!law.outside_domain(p, mode, x).empty()) return x;
    const auto D = law.drucker_tangent(p, l1, l2);
    if (!(D[0] + D[2] > 0.0) || !(D[0] * D[2] - D[1] * D[1] > 0.0)) return x;
  }
  return 0.0;
}

}  // namespace fitlib::model
