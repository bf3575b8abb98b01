// The visco-hyperelastic card (docs/hyperelastic.md §"Visco-hyperelastic"): a hyperelastic base
// giving the long-term response and a Prony series of relative shear moduli g_i, τ_i, the
// finite-strain form of Abaqus's *HYPERELASTIC (long term) + *VISCOELASTIC, TIME=PRONY (Simo 1987):
//   τ_dev(t) = ∫ g(t − s) dτ0_dev(s), g(t) = 1 − Σ g_i (1 − e^(−t/τ_i)), τ0 = τ∞/(1 − Σ g_i),
// with the bulk response elastic (k_i = 0). The base parameters come first, so the base law reads
// the same parameter vector (Model::hyperelastic).
#include <cmath>
#include <complex>

#include "fitlib/core/error.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/time_series.hpp"
#include "points.hpp"

namespace fitlib::model {
namespace {

using core::ParameterSpec;

struct Prony {
  std::vector<double> g, tau_s;
  double sum() const {
    double s = 0.0;
    for (double x : g) s += x;
    return s;
  }
};

// Exact for τ0 linear over the step: q_{n+1} = τ0_n − e^(−x)(τ0_n − q_n) + β Δτ0,
// β = 1 − (1 − e^(−x))/x, x = Δt/τ_i (q_i = ∫ (1 − e^(−(t − s)/τ_i)) dτ0_dev).
double beta(double x) { return x < 1e-8 ? 0.5 * x : 1.0 + std::expm1(-x) / x; }

class ViscoHyperelasticPoint final : public MaterialPoint {
 public:
  ViscoHyperelasticPoint(MaterialPointPtr base, Prony prony, std::string description)
      : base_(std::move(base)), prony_(std::move(prony)), description_(std::move(description)) {}
  std::string describe() const override { return description_; }
  // τ0_dev of the last converged step, then q_i per term (Voigt, 6 each).
  std::size_t state_size() const override { return 6 * (prony_.g.size() + 1); }
  std::vector<double> initial_state() const override { return std::vector<double>(state_size(), 0.0); }

  Vector6 update(const double* state_n, const Vector6& strain, double dt_s, double T, double* state_next,
                 Matrix6* tangent) const override {
    if (!(dt_s >= 0.0)) throw core::UsageError(description_ + ": the time step must be ≥ 0");
    const Vector6 s = stress(state_n, strain, dt_s, T, state_next);
    if (tangent) {  // central differences of this very update (pure in state_n and ε)
      std::vector<double> scratch(state_size());
      const double h = 1e-6;
      for (int k = 0; k < 6; ++k) {
        Vector6 a = strain, b = strain;
        a[k] += h, b[k] -= h;
        tangent->col(k) = (stress(state_n, a, dt_s, T, scratch.data()) - stress(state_n, b, dt_s, T, scratch.data())) / (2 * h);
      }
    }
    return s;
  }

  ComplexMatrix6 complex_stiffness(double f_Hz, double T) const override {
    const ComplexMatrix6 C = base_->complex_stiffness(f_Hz, T);
    const double G_inf = C(5, 5).real(), K = (C(0, 0).real() + 2.0 * C(0, 1).real()) / 3.0;
    const double G0 = G_inf / (1.0 - prony_.sum());
    std::complex<double> G = G_inf;
    for (std::size_t i = 0; i < prony_.g.size(); ++i) {
      const std::complex<double> iwt(0.0, 2.0 * M_PI * f_Hz * prony_.tau_s[i]);
      G += G0 * prony_.g[i] * iwt / (1.0 + iwt);
    }
    return points::isotropic_stiffness<std::complex<double>>(K, G);
  }

 private:
  Vector6 stress(const double* state_n, const Vector6& strain, double dt, double T, double* next) const {
    const Vector6 inf = base_->update(nullptr, strain, dt, T, nullptr, nullptr);
    const double mean = (inf[0] + inf[1] + inf[2]) / 3.0;
    Vector6 dev0 = inf;
    dev0.head<3>().array() -= mean;
    dev0 /= 1.0 - prony_.sum();  // instantaneous deviatoric stress
    const Eigen::Map<const Vector6> dev0_n(state_n);
    Vector6 s = dev0;
    for (std::size_t i = 0; i < prony_.g.size(); ++i) {
      const double x = dt / prony_.tau_s[i];
      const Eigen::Map<const Vector6> q_n(state_n + 6 * (i + 1));
      const Vector6 q = dev0_n - std::exp(-x) * (dev0_n - q_n) + beta(x) * (dev0 - dev0_n);
      Eigen::Map<Vector6>(next + 6 * (i + 1)) = q;
      s -= prony_.g[i] * q;
    }
    Eigen::Map<Vector6> dev0_next(next);
    dev0_next = dev0;
    s.head<3>().array() += mean;
    return s;
  }

  MaterialPointPtr base_;
  Prony prony_;
  std::string description_;
};

class ViscoHyperelasticModel final : public Model {
 public:
  ViscoHyperelasticModel(ModelPtr base, nlohmann::json base_options, int terms)
      : base_(std::move(base)), base_options_(std::move(base_options)), terms_(terms) {
    specs_ = base_->parameters();
    for (int i = 1; i <= terms; ++i)
      specs_.push_back({"g_" + std::to_string(i), "-", 0.0, 1.0, core::Transform::linear, "viscous", 0.1, true});
    for (int i = 1; i <= terms; ++i)
      specs_.push_back({"tau_" + std::to_string(i), "s", 0.0, std::numeric_limits<double>::infinity(),
                        core::Transform::log, "viscous", std::pow(10.0, i - 2), false});
  }
  std::string kind() const override { return "visco-hyperelastic"; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  nlohmann::json options() const override {
    return {{"base", base_->kind()}, {"base_options", base_options_}, {"terms", terms_}};
  }
  TestMode native_mode() const override { return TestMode::shear; }
  const HyperelasticLaw* hyperelastic() const override { return base_->hyperelastic(); }
  double bulk_modulus(const double* p) const override { return base_->bulk_modulus(p); }

  // The small-strain Maxwell series in shear: G∞ = μ0 of the base, G_i = G0 g_i.
  bool maxwell_series(const double* p, MaxwellSeries* out) const override {
    const Prony s = prony(p);
    out->relaxed = base_->hyperelastic()->initial_shear_modulus(p);
    const double G0 = out->relaxed / (1.0 - s.sum());
    out->moduli.clear(), out->times_s = s.tau_s;
    for (double g : s.g) out->moduli.push_back(G0 * g);
    return true;
  }
  Moduli<double> moduli(const double* p, const TestCondition& c) const override {
    MaxwellSeries s;
    maxwell_series(p, &s);
    std::complex<double> G = s.relaxed;
    for (std::size_t i = 0; i < s.moduli.size(); ++i) {
      const std::complex<double> iwt(0.0, 2.0 * M_PI * c.frequency_Hz * s.times_s[i]);
      G += s.moduli[i] * iwt / (1.0 + iwt);
    }
    std::complex<double> m = G;
    const double K = bulk_modulus(p);
    if (c.mode == TestMode::uniaxial) m = std::isnan(K) ? 3.0 * G : 9.0 * K * G / (3.0 * K + G);
    if (c.mode == TestMode::bulk) {
      if (std::isnan(K)) throw core::UsageError("visco-hyperelastic: an incompressible base has no bulk modulus");
      m = K;
    }
    return {m.real(), m.imag(), m.real()};
  }
  // Derivatives by central differences: the card is combined from two fits, not fitted itself.
  Moduli<double> moduli(const double* p, const TestCondition& c, Eigen::Ref<Eigen::MatrixXd> J) const override {
    std::vector<double> a(p, p + size()), b = a;
    for (std::size_t k = 0; k < size(); ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(p[k]));
      a[k] += h, b[k] -= h;
      const Moduli<double> u = moduli(a.data(), c), d = moduli(b.data(), c);
      J(0, k) = (u.storage - d.storage) / (2 * h), J(1, k) = (u.loss - d.loss) / (2 * h), J(2, k) = (u.mean - d.mean) / (2 * h);
      a[k] = b[k] = p[k];
    }
    return moduli(p, c);
  }
  std::vector<double> stress_response(const double* p, const TestCondition& c, const StrainHistory& h) const override {
    MaxwellSeries s;
    maxwell_series(p, &s);
    if (c.mode != TestMode::shear) throw core::UsageError("visco-hyperelastic: stress_response in shear only");
    return s.stress(h);  // small strain
  }
  double relaxation_modulus(const double* p, const TestCondition& c, double t) const override {
    MaxwellSeries s;
    maxwell_series(p, &s);
    if (c.mode != TestMode::shear) throw core::UsageError("visco-hyperelastic: relaxation modulus in shear only");
    return s.relaxation(t);
  }
  double creep_compliance(const double* p, const TestCondition& c, double t) const override {
    MaxwellSeries s;
    maxwell_series(p, &s);
    if (c.mode != TestMode::shear) throw core::UsageError("visco-hyperelastic: creep compliance in shear only");
    return s.creep(t);
  }
  std::shared_ptr<const MaterialPoint> material_point(const double* p, const PointOptions& options) const override {
    PointOptions o = options;
    o.fidelity = core::Fidelity::complete;
    const auto point = std::make_shared<ViscoHyperelasticPoint>(base_->material_point(p, o), prony(p),
                                                                "visco-hyperelastic (" + base_->kind() + ", " +
                                                                    std::to_string(terms_) + " Prony terms)");
    if (options.fidelity == core::Fidelity::elastic)
      return points::elastic_equivalent(*point, options.frequency_Hz, options.temperature_C);
    return point;
  }

 private:
  Prony prony(const double* p) const {
    Prony s;
    const std::size_t nb = base_->size();
    for (int i = 0; i < terms_; ++i) s.g.push_back(p[nb + i]), s.tau_s.push_back(p[nb + terms_ + i]);
    if (!(s.sum() < 1.0)) throw core::UsageError("visco-hyperelastic: the relative moduli g_i must sum to < 1");
    return s;
  }

  ModelPtr base_;
  nlohmann::json base_options_;
  int terms_;
  std::vector<ParameterSpec> specs_;
};

}  // namespace

bool is_visco_hyperelastic_kind(const std::string& kind) { return kind == "visco-hyperelastic"; }

ModelPtr make_visco_hyperelastic_model(const nlohmann::json& options) {
  if (!options.is_object() || !options.contains("base") || !options["base"].is_string())
    throw core::UsageError("visco-hyperelastic: option base (a hyperelastic kind) is required");
  for (const auto& [key, value] : options.items())
    if (key != "base" && key != "base_options" && key != "terms")
      throw core::UsageError("visco-hyperelastic: unknown model option '" + key + "' (base, base_options, terms)");
  const std::string base = options["base"].get<std::string>();
  if (!is_hyperelastic_kind(base)) throw core::UsageError("visco-hyperelastic: base '" + base + "' is not hyperelastic");
  const nlohmann::json base_options = options.value("base_options", nlohmann::json::object());
  const nlohmann::json terms = options.value("terms", nlohmann::json(1));
  if (!terms.is_number_integer() || terms.get<int>() < 1 || terms.get<int>() > 100)
    throw core::UsageError("visco-hyperelastic: option terms must be an integer in 1..100");
  const ModelPtr b = make_hyperelastic_model(base, base_options);
  return std::make_shared<ViscoHyperelasticModel>(b, b->options(), terms.get<int>());
}

}  // namespace fitlib::model
