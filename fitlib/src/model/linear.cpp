#include "fitlib/model/linear.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/autodiff_model.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/time_series.hpp"
#include "points.hpp"

namespace fitlib::model {
namespace {

using core::ParameterSpec;
using core::Transform;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGasConstant_kJ_molK = 8.314462618e-3;
constexpr double kMinLinearFactor = 1e-3;  // g(T) guard: the factor never reaches zero

inline double value_of(double x) { return x; }
template <typename T, int N>
double value_of(const ceres::Jet<T, N>& x) { return x.a; }

ParameterSpec modulus_spec(const std::string& name, double start, const std::string& group) {
  return {name, "MPa", 0.0, kInf, Transform::log, group, start, true};
}
ParameterSpec time_spec(const std::string& name, double start) {
  return {name, "s", 0.0, kInf, Transform::log, "time", start, false};
}
std::string prefix_for(TestMode mode) {
  return mode == TestMode::shear ? "G" : mode == TestMode::uniaxial ? "E" : "K";
}
// Log-spaced times between 1/ω_max and 1/ω_min (one term: their geometric mean).
std::vector<double> time_grid(const DataSummary& d, int n) {
  const double lo = 1.0 / std::max(d.omega_max_rad_s, 1e-300);
  const double hi = 1.0 / std::max(d.omega_min_rad_s, 1e-300);
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i)
    t[i] = n == 1 ? std::sqrt(lo * hi) : lo * std::pow(hi / lo, double(i) / (n - 1));
  return t;
}

// Start of a series model: the first constant, n equal weights, times on the data's grid.
std::vector<double> series_start(double first, double weight, const DataSummary& d, int n) {
  std::vector<double> p{first};
  p.insert(p.end(), static_cast<std::size_t>(n), weight);
  for (double t : time_grid(d, n)) p.push_back(t);
  return p;
}

// ---- kernels: complex modulus re + i·im at angular frequency ω (reference temperature) ----

struct Prony {
  static constexpr const char* kKind = "prony";
  static constexpr bool kHasTerms = true;
  static void specs(std::vector<ParameterSpec>& out, int n, const std::string& P) {
    out.push_back(modulus_spec(P + "_inf", 1.0, "elastic"));
    for (int i = 1; i <= n; ++i) out.push_back(modulus_spec(P + "_" + std::to_string(i), 1.0, "viscous"));
    for (int i = 1; i <= n; ++i) out.push_back(time_spec("tau_" + std::to_string(i), std::pow(10.0, i - 1 - n / 2)));
  }
  template <typename T>
  static void complex(const T* p, int n, const T& omega, T& re, T& im) {
    re = p[0];
    im = T(0.0);
    for (int i = 0; i < n; ++i) {
      const T wt = omega * p[1 + n + i];
      const T den = T(1.0) + wt * wt;
      re += p[1 + i] * wt * wt / den;
      im += p[1 + i] * wt / den;
    }
  }
  template <typename T>
  static T relaxed(const T* p, int) { return p[0]; }
  static MaxwellSeries series(const double* p, int n) {
    return {p[0], std::vector<double>(p + 1, p + 1 + n), std::vector<double>(p + 1 + n, p + 1 + 2 * n)};
  }
  static std::vector<double> start(const DataSummary& d, int n) {
    const double spread = std::max(d.storage_max_MPa - d.storage_min_MPa, 1e-3 * d.storage_max_MPa);
    return series_start(std::max(d.storage_min_MPa, 1e-9), std::max(spread / n, 1e-12), d, n);
  }
};

// T + τ_T Ṫ = S(ε + τ_ε ε̇): a Maxwell series with M∞ = S, M_1 = S(τ_ε/τ_T − 1), τ_1 = τ_T.
struct Zener3 {
  static constexpr const char* kKind = "zener3";
  static constexpr bool kHasTerms = false;
  static void specs(std::vector<ParameterSpec>& out, int, const std::string& P) {
    out.push_back(modulus_spec(P + "_S", 1.0, "elastic"));
    out.push_back(time_spec("tau_T", 0.2));
    out.push_back(time_spec("tau_eps", 0.3));
  }
  template <typename T>
  static void complex(const T* p, int, const T& omega, T& re, T& im) {
    // S(1 + iωτ_ε)/(1 + iωτ_T) = S[(1 + ω²τ_ετ_T) + iω(τ_ε − τ_T)]/(1 + ω²τ_T²)
    const T den = T(1.0) + omega * omega * p[1] * p[1];
    re = p[0] * (T(1.0) + omega * omega * p[2] * p[1]) / den;
    im = p[0] * omega * (p[2] - p[1]) / den;
  }
  template <typename T>
  static T relaxed(const T* p, int) { return p[0]; }
  static MaxwellSeries series(const double* p, int) { return three_parameter_solid(p[0], p[1], p[2]); }
  static std::vector<double> start(const DataSummary& d, int) {
    const double t = 1.0 / std::sqrt(std::max(d.omega_min_rad_s * d.omega_max_rad_s, 1e-300));
    return {std::max(d.storage_min_MPa, 1e-9), t, t * std::max(d.storage_max_MPa / std::max(d.storage_min_MPa, 1e-9), 1.01)};
  }
};

struct Retardation {
  static constexpr const char* kKind = "retardation";
  static constexpr bool kHasTerms = true;
  static void specs(std::vector<ParameterSpec>& out, int n, const std::string&) {
    out.push_back({"J_g", "1/MPa", 0.0, kInf, Transform::log, "elastic", 1.0, false});
    for (int i = 1; i <= n; ++i)
      out.push_back({"L_" + std::to_string(i), "1/MPa", 0.0, kInf, Transform::log, "viscous", 1.0, false});
    for (int i = 1; i <= n; ++i) out.push_back(time_spec("lambda_" + std::to_string(i), std::pow(10.0, i - 1 - n / 2)));
  }
  template <typename T>
  static void complex(const T* p, int n, const T& omega, T& re, T& im) {
    T jre = p[0], jim = T(0.0);  // J* = J′ − iJ″
    for (int i = 0; i < n; ++i) {
      const T wl = omega * p[1 + n + i];
      const T den = T(1.0) + wl * wl;
      jre += p[1 + i] / den;
      jim += p[1 + i] * wl / den;
    }
    const T mag2 = jre * jre + jim * jim;
    re = jre / mag2;
    im = jim / mag2;
  }
  template <typename T>
  static T relaxed(const T* p, int n) {
    T j = p[0];
    for (int i = 0; i < n; ++i) j += p[1 + i];
    return T(1.0) / j;
  }
  static KelvinSeries kelvin(const double* p, int n) {
    return {p[0], std::vector<double>(p + 1, p + 1 + n), std::vector<double>(p + 1 + n, p + 1 + 2 * n)};
  }
  static std::vector<double> start(const DataSummary& d, int n) {
    const double jg = 1.0 / std::max(d.storage_max_MPa, 1e-9);
    const double jr = 1.0 / std::max(d.storage_min_MPa, 1e-9);
    return series_start(jg, std::max((jr - jg) / n, 1e-3 * jg), d, n);
  }
};

struct FractionalZener {
  static constexpr const char* kKind = "fractional-zener";
  static constexpr bool kHasTerms = false;
  static void specs(std::vector<ParameterSpec>& out, int, const std::string& P) {
    out.push_back(modulus_spec(P + "_0", 1.0, "elastic"));
    out.push_back(modulus_spec(P + "_delta", 10.0, "viscous"));
    out.push_back(time_spec("tau", 1.0));
    out.push_back({"alpha", "-", 0.02, 0.98, Transform::linear, "shape", 0.5, false});
  }
  template <typename T>
  static void complex(const T* p, int, const T& omega, T& re, T& im) {
    using std::cos;
    using std::exp;
    using std::log;
    using std::sin;
    // z = (iωτ)^α = r(cos θ + i sin θ), r = (ωτ)^α, θ = απ/2; z/(1 + z).
    const T r = exp(p[3] * log(omega * p[2]));
    const T theta = p[3] * T(core::kPi / 2.0);
    const T c = cos(theta), s = sin(theta);
    const T den = T(1.0) + T(2.0) * r * c + r * r;
    re = p[0] + p[1] * (r * r + r * c) / den;
    im = p[1] * r * s / den;
  }
  template <typename T>
  static T relaxed(const T* p, int) { return p[0]; }
  static MaxwellSeries series(const double* p, int, const FractionalQuadrature& q = {}) {
    // Cole–Cole spectrum: z/(1+z) = ∫ h(s) iωθ/(1 + iωθ) ds, θ = τ e^s,
    // h(s) = sin(απ) / (2π (cosh(αs) + cos(απ))); trapezoidal rule, weights renormalised to 1.
    const double alpha = p[3];
    const double ds = std::log(10.0) / q.modes_per_decade;
    const int half = static_cast<int>(std::ceil(q.decades_each_side * q.modes_per_decade));
    MaxwellSeries m{p[0], {}, {}};
    double total = 0.0;
    for (int k = -half; k <= half; ++k) {
      const double s = k * ds;
      const double h = std::sin(alpha * core::kPi) /
                       (2.0 * core::kPi * (std::cosh(alpha * s) + std::cos(alpha * core::kPi)));
      m.moduli.push_back(h * ds);
      m.times_s.push_back(p[2] * std::exp(s));
      total += h * ds;
    }
    for (double& mi : m.moduli) mi *= p[1] / total;
    return m;
  }
  static std::vector<double> start(const DataSummary& d, int) {
    const double t = 1.0 / std::sqrt(std::max(d.omega_min_rad_s * d.omega_max_rad_s, 1e-300));
    return {std::max(d.storage_min_MPa, 1e-9), std::max(d.storage_max_MPa - d.storage_min_MPa, 1e-6), t, 0.5};
  }
};

// Parameter name of the polynomial law's coefficient of (T − T_ref)^k.
std::string polynomial_name(int k) { return "poly_C" + std::to_string(k); }

struct Options {
  TestMode mode = TestMode::shear;
  int terms = 4;
  ShiftLaw law = ShiftLaw::none;
  double reference_C = 23.0;
  int polynomial_degree = 3;  // temperature_law polynomial: log10 a_T = Σ_k C_k (T − T_ref)^k
  bool vertical_shift = false, linear_factor = false, bulk_modulus = false;
};

// A whole-number option; a float with a fraction or beyond int's range is refused (not cast).
int whole_option(const nlohmann::json& value, const std::string& key) {
  const double x = value.get<double>();
  if (!(x == std::floor(x) && std::abs(x) <= std::numeric_limits<int>::max()))
    throw core::UsageError("model option '" + key + "' must be a whole number");
  return static_cast<int>(x);
}

Options parse_options(const nlohmann::json& j, bool has_terms) {
  Options o;
  if (!j.is_null() && !j.is_object()) throw core::UsageError("model options must be a JSON object");
  for (auto it = j.begin(); !j.is_null() && it != j.end(); ++it) {
    const std::string& key = it.key();
    try {
      if (key == "mode") o.mode = parse_test_mode(it->get<std::string>());
      else if (key == "terms" && has_terms) o.terms = whole_option(*it, key);
      else if (key == "temperature_law") o.law = parse_shift_law(it->get<std::string>());
      else if (key == "reference_C") o.reference_C = it->get<double>();
      else if (key == "polynomial_degree") o.polynomial_degree = whole_option(*it, key);
      else if (key == "vertical_shift") o.vertical_shift = it->get<bool>();
      else if (key == "linear_factor") o.linear_factor = it->get<bool>();
      else if (key == "bulk_modulus") o.bulk_modulus = it->get<bool>();
      else throw core::UsageError("unknown model option '" + key + "'");
    } catch (const nlohmann::json::exception& e) {
      throw core::UsageError("model option '" + key + "': wrong type (" + e.what() + ")");
    }
  }
  if (o.polynomial_degree < 1 || o.polynomial_degree > kMaxShiftPolynomialDegree)
    throw core::UsageError("model option 'polynomial_degree' must be between 1 and " +
                           std::to_string(kMaxShiftPolynomialDegree) + ", got " + std::to_string(o.polynomial_degree));
  if (o.terms < 1 || o.terms > kMaxSeriesTerms)
    throw core::UsageError("model option 'terms' must be between 1 and " + std::to_string(kMaxSeriesTerms) +
                           ", got " + std::to_string(o.terms));
  return o;
}

template <class Kernel>
class LinearModel : public AutodiffModel<LinearModel<Kernel>> {
 public:
  explicit LinearModel(const Options& o) : o_(o) {
    const int n = Kernel::kHasTerms ? o.terms : 0;
    Kernel::specs(specs_, n, prefix_for(o.mode));
    kernel_size_ = specs_.size();
    if (o.bulk_modulus) {
      k_index_ = specs_.size();
      specs_.push_back({"K", "MPa", 0.0, kInf, Transform::log, "volumetric", 2000.0, false});
    }
    shift_index_ = specs_.size();
    if (o.law == ShiftLaw::wlf) {
      specs_.push_back({"C1", "-", 0.0, 1e3, Transform::log, "shift", 10.0, false});
      specs_.push_back({"C2", "K", 0.0, 1e4, Transform::log, "shift", 100.0, false});
    } else if (o.law == ShiftLaw::arrhenius) {
      specs_.push_back({"activation_energy", "kJ/mol", 0.0, 1e4, Transform::log, "shift", 100.0, false});
    } else if (o.law == ShiftLaw::polynomial) {
      for (int k = 1; k <= o.polynomial_degree; ++k)
        specs_.push_back({polynomial_name(k), k == 1 ? "1/K" : "1/K^" + std::to_string(k), -1e6, 1e6,
                          Transform::linear, "shift", k == 1 ? -0.1 : 0.0, false});
    }
    factor_index_ = specs_.size();
    if (o.linear_factor) specs_.push_back({"c_T", "1/degC", -1.0, 1.0, Transform::linear, "temperature", 0.0, false});
  }

  using AutodiffModel<LinearModel<Kernel>>::moduli;

  // Prony in its own mode has a cheap closed-form Jacobian (the fitter's hot path); everything
  // else goes through automatic differentiation.
  Moduli<double> moduli(const double* p, const TestCondition& c,
                        Eigen::Ref<Eigen::MatrixXd> jacobian) const override {
    if constexpr (std::is_same_v<Kernel, Prony>) {
      if (c.mode == o_.mode) return prony_with_jacobian(p, c, jacobian);
    }
    return AutodiffModel<LinearModel<Kernel>>::moduli(p, c, jacobian);
  }

  std::string kind() const override { return Kernel::kKind; }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  TestMode native_mode() const override { return o_.mode; }

  nlohmann::json options() const override {
    nlohmann::json j;
    j["mode"] = to_string(o_.mode);
    if (Kernel::kHasTerms) j["terms"] = o_.terms;
    j["temperature_law"] = to_string(o_.law);
    j["reference_C"] = o_.reference_C;
    if (o_.law == ShiftLaw::polynomial) j["polynomial_degree"] = o_.polynomial_degree;
    j["vertical_shift"] = o_.vertical_shift;
    j["linear_factor"] = o_.linear_factor;
    j["bulk_modulus"] = o_.bulk_modulus;
    return j;
  }

  nlohmann::json temperature_law(const double* p) const override {
    nlohmann::json j{{"reference_C", o_.reference_C}, {"vertical_shift", o_.vertical_shift}};
    if (o_.law == ShiftLaw::wlf) {
      j["law"] = "wlf";
      j["C1"] = p[shift_index_];
      j["C2_K"] = p[shift_index_ + 1];
    } else if (o_.law == ShiftLaw::arrhenius) {
      j["law"] = "arrhenius";
      j["activation_energy_kJ_mol"] = p[shift_index_];
    } else if (o_.law == ShiftLaw::polynomial) {
      j["law"] = "polynomial";
      j["coefficients"] = std::vector<double>(p + shift_index_, p + shift_index_ + o_.polynomial_degree);
    } else {
      j["law"] = "none";
    }
    if (o_.linear_factor) j["c_T_per_C"] = p[factor_index_];
    return j;
  }

  bool kelvin_series(const double* p, KelvinSeries* out) const override {
    if constexpr (std::is_same_v<Kernel, Retardation>) {
      *out = Kernel::kelvin(p, terms());
      return true;
    }
    return false;
  }

  double bulk_modulus(const double* p) const override {
    return o_.bulk_modulus ? p[k_index_] : std::numeric_limits<double>::quiet_NaN();
  }

  TemperatureLawInfo temperature_law_info() const override {
    TemperatureLawInfo info;
    info.reference_C = o_.reference_C;
    info.vertical_shift = o_.vertical_shift;
    info.linear_factor = o_.linear_factor;
    if (o_.law == ShiftLaw::wlf) {
      info.law = model::ShiftLaw::wlf;
      info.shift_parameters = {int(shift_index_), int(shift_index_ + 1)};
      info.pole_parameter = int(shift_index_ + 1);
    } else if (o_.law == ShiftLaw::arrhenius) {
      info.law = model::ShiftLaw::arrhenius;
      info.shift_parameters = {int(shift_index_)};
    } else if (o_.law == ShiftLaw::polynomial) {
      info.law = model::ShiftLaw::polynomial;
      for (int k = 0; k < o_.polynomial_degree; ++k) info.shift_parameters.push_back(int(shift_index_) + k);
    }
    return info;
  }

  std::string temperature_out_of_law(const double* p, double temperature_C) const override {
    if (!std::isfinite(temperature_C)) return {};  // NaN: the reference temperature (Model's contract)
    const double dT = temperature_C - o_.reference_C;
    if (o_.law == ShiftLaw::wlf && !(p[shift_index_ + 1] + dT > 0.0))
      return "the WLF law has its pole at T_ref - C2 = " + core::format_number(o_.reference_C - p[shift_index_ + 1]) +
             " degC: it describes a material only above it";
    if (!o_.linear_factor) return {};
    return linear_factor_out_of_law(specs_[factor_index_].name, p[factor_index_], o_.reference_C, temperature_C,
                                    kMinLinearFactor);
  }

  TemperatureFactors temperature_factors(const double* p, double temperature_C) const override {
    TestCondition c;
    c.temperature_C = temperature_C;
    TemperatureFactors f;
    temperature_factors(p, c, f.shift_factor, f.scale);
    return f;
  }

  // docs/model.md §"Linear viscoelastic point": the shear series of the kernel (Kelvin chains
  // converted exactly, the fractional Zener by its quadrature) and an elastic bulk modulus.
  std::shared_ptr<const MaterialPoint> material_point(const double* p,
                                                      const PointOptions& options) const override {
    const double K = std::isnan(options.bulk_modulus_MPa) ? bulk_modulus(p) : options.bulk_modulus_MPa;
    const std::string name = std::string(Kernel::kKind) + " (" + to_string(o_.mode) + " card)";
    if (o_.mode == TestMode::bulk)
      throw core::UsageError(name + ": a bulk card alone gives no material point (no shear part)");
    if (!(K > 0.0))
      throw core::UsageError(name + ": a material point needs a bulk modulus K > 0 (fit with "
                             "--bulk-modulus, or give the point's bulk modulus)");
    if (options.fidelity == core::Fidelity::elastic) {
      TestCondition c;
      c.mode = o_.mode;
      c.frequency_Hz = options.frequency_Hz;
      c.temperature_C = options.temperature_C;
      const double m = this->moduli(p, c).storage;
      const double G = o_.mode == TestMode::shear ? m : 3.0 * K * m / (9.0 * K - m);
      const double K_T = K * temperature_factors(p, options.temperature_C).scale;  // as moduli()
      if (!(G > 0.0))
        throw core::NumericalError(name + ": storage modulus not below 9K, no elastic equivalent");
      return points::elastic_point(points::isotropic_stiffness(K_T, G), name + ", elastic");
    }
    if (o_.mode != TestMode::shear)
      throw core::UsageError(name + ": the 3-D viscoelastic point needs a shear card (a uniaxial "
                             "relaxation series has no finite shear series); use the elastic "
                             "fidelity or fit the shear modulus");
    MaxwellSeries shear;
    if constexpr (std::is_same_v<Kernel, Retardation>) shear = Kernel::kelvin(p, terms()).to_maxwell();
    else shear = Kernel::series(p, terms());
    auto self = std::make_shared<const LinearModel>(*this);
    std::vector<double> values(p, p + specs_.size());
    auto temperature = [self, values](double T) { return self->temperature_factors(values.data(), T); };
    return points::linear_viscoelastic_point(std::move(shear), MaxwellSeries{K, {}, {}},
                                             std::move(temperature), name);
  }

  bool maxwell_series(const double* p, MaxwellSeries* out) const override {
    if constexpr (std::is_same_v<Kernel, Prony> || std::is_same_v<Kernel, Zener3>) {
      *out = Kernel::series(p, terms());
      return true;
    }
    return false;
  }

  std::vector<double> initial_parameters(const DataSummary& d) const override {
    std::vector<double> p = this->default_parameters();
    const auto k = Kernel::start(d, terms());
    std::copy(k.begin(), k.end(), p.begin());
    if (o_.law == ShiftLaw::wlf) {
      // Keep the start clear of the WLF pole: C2 + T − T_ref > 0 for all data.
      p[shift_index_ + 1] = std::max(100.0, 1.5 * (o_.reference_C - d.temperature_min_C) + 10.0);
    }
    return p;
  }

  template <typename T>
  Moduli<T> evaluate(const T* p, const TestCondition& c) const {
    T shift_factor, scale;
    temperature_factors(p, c, shift_factor, scale);
    const T omega = T(core::angular_frequency(c.frequency_Hz)) * shift_factor;
    T re, im;
    Kernel::complex(p, terms(), omega, re, im);
    T relaxed = Kernel::template relaxed<T>(p, terms());
    if (c.mode != o_.mode) convert_mode(p, c.mode, re, im, relaxed);
    return {scale * re, scale * im, scale * relaxed};
  }

  std::vector<double> stress_response(const double* p, const TestCondition& c,
                                      const StrainHistory& history) const override {
    double shift_factor, scale;
    temperature_factors(p, c, shift_factor, scale);
    if (c.mode != o_.mode) {
      if (c.mode == TestMode::bulk && o_.bulk_modulus) {
        std::vector<double> s(history.strain);
        for (double& x : s) x *= p[k_index_];
        return s;
      }
      throw core::UsageError(std::string("time response in ") + to_string(c.mode) +
                             " of a " + to_string(o_.mode) + " card is not available");
    }
    StrainHistory reduced = history;  // time–temperature superposition: t_r = t/a_T
    for (double& t : reduced.time_s) t /= shift_factor;
    std::vector<double> s = time_domain_stress(p, reduced);
    for (double& x : s) x *= scale;
    return s;
  }

  double relaxation_modulus(const double* p, const TestCondition& c, double t_s) const override {
    double shift_factor, scale;
    temperature_factors(p, c, shift_factor, scale);
    require_native(c, "relaxation modulus");
    const double tr = t_s / shift_factor;
    if constexpr (std::is_same_v<Kernel, Retardation>) return scale * Kernel::kelvin(p, terms()).relaxation(tr);
    else return scale * Kernel::series(p, terms()).relaxation(tr);
  }

  double creep_compliance(const double* p, const TestCondition& c, double t_s) const override {
    double shift_factor, scale;
    temperature_factors(p, c, shift_factor, scale);
    require_native(c, "creep compliance");
    const double tr = t_s / shift_factor;
    if constexpr (std::is_same_v<Kernel, Retardation>) return Kernel::kelvin(p, terms()).creep(tr) / scale;
    else return Kernel::series(p, terms()).creep(tr) / scale;
  }

 private:
  int terms() const { return Kernel::kHasTerms ? o_.terms : 0; }

  Moduli<double> prony_with_jacobian(const double* p, const TestCondition& c,
                                     Eigen::Ref<Eigen::MatrixXd> J) const {
    // Temperature parameters (at most three, after the kernel and K) by forward differentiation,
    // only when the model has any.
    const size_t n = specs_.size();
    double a_T, g_T;
    double da_T[3] = {0.0, 0.0, 0.0}, dg_T[3] = {0.0, 0.0, 0.0};
    if (shift_index_ < n) {
      using Jet = ceres::Jet<double, 3>;
      std::vector<Jet> pj(n);
      for (size_t i = 0; i < n; ++i) {
        pj[i] = Jet(p[i]);
        if (i >= shift_index_) pj[i].v[i - shift_index_] = 1.0;
      }
      Jet shift_jet, scale_jet;
      temperature_factors(pj.data(), c, shift_jet, scale_jet);
      a_T = shift_jet.a;
      g_T = scale_jet.a;
      for (int k = 0; k < 3; ++k) {
        da_T[k] = shift_jet.v[k];
        dg_T[k] = scale_jet.v[k];
      }
    } else {
      temperature_factors(p, c, a_T, g_T);
    }
    const double omega0 = core::angular_frequency(c.frequency_Hz);
    const double omega = omega0 * a_T, g = g_T;
    const int N = terms();
    double re = p[0], im = 0.0, dre_domega = 0.0, dim_domega = 0.0;
    // Every entry is written below or here (no J.setZero() pass: it was a memset of the whole
    // 3 x n block per data point, ≈ 3 % of `fitcli fit --terms auto`).
    J(0, 0) = g;
    J(1, 0) = 0.0;
    J(2, 0) = g;
    J.row(2).segment(1, 2 * N).setZero();
    J.rightCols(J.cols() - 1 - 2 * N).setZero();
    for (int i = 0; i < N; ++i) {
      const double M = p[1 + i], tau = p[1 + N + i], w = omega * tau, d = 1.0 + w * w;
      re += M * w * w / d;
      im += M * w / d;
      J(0, 1 + i) = g * w * w / d;
      J(1, 1 + i) = g * w / d;
      const double dre_dw = 2.0 * M * w / (d * d), dim_dw = M * (1.0 - w * w) / (d * d);
      J(0, 1 + N + i) = g * dre_dw * omega;
      J(1, 1 + N + i) = g * dim_dw * omega;
      dre_domega += dre_dw * tau;
      dim_domega += dim_dw * tau;
    }
    for (size_t i = shift_index_; i < n; ++i) {
      const int k = static_cast<int>(i - shift_index_);
      const double domega = omega0 * da_T[k];
      J(0, i) = g * dre_domega * domega + re * dg_T[k];
      J(1, i) = g * dim_domega * domega + im * dg_T[k];
      J(2, i) = p[0] * dg_T[k];
    }
    return {g * re, g * im, g * p[0]};
  }

  void require_native(const TestCondition& c, const char* what) const {
    if (c.mode != o_.mode)
      throw core::UsageError(std::string(what) + " in " + to_string(c.mode) + " of a " +
                             to_string(o_.mode) + " card is not available");
  }

  std::vector<double> time_domain_stress(const double* p, const StrainHistory& h) const {
    if constexpr (std::is_same_v<Kernel, Retardation>) return Kernel::kelvin(p, terms()).stress(h);
    else return Kernel::series(p, terms()).stress(h);
  }

  // Horizontal shift a_T (reduced frequency ω·a_T) and vertical scale (entropic T/T_ref and
  // the linear factor g(T)).
  template <typename T>
  void temperature_factors(const T* p, const TestCondition& c, T& shift_factor, T& scale) const {
    using std::exp;
    shift_factor = T(1.0);
    scale = T(1.0);
    if (!c.has_temperature()) return;
    const double dT = c.temperature_C - o_.reference_C;
    if (o_.law == ShiftLaw::wlf) {
      const T c1 = p[shift_index_], c2 = p[shift_index_ + 1];
      if (!(value_of(c2) + dT > 0.0))
        throw core::InputError("temperature " + std::to_string(c.temperature_C) +
                               " degC is at or beyond the WLF pole (T_ref − C2 = " +
                               std::to_string(o_.reference_C - value_of(c2)) + " degC)");
      shift_factor = exp(-c1 * T(dT) / (c2 + T(dT)) * T(std::log(10.0)));
    } else if (o_.law == ShiftLaw::arrhenius) {
      const double inv = 1.0 / core::kelvin_from_celsius(c.temperature_C) -
                         1.0 / core::kelvin_from_celsius(o_.reference_C);
      shift_factor = exp(p[shift_index_] / T(kGasConstant_kJ_molK) * T(inv));
    } else if (o_.law == ShiftLaw::polynomial) {
      // log10 a_T = Σ_{k=1..d} C_k (T − T_ref)^k (docs/fitting.md, "Temperature laws"); Horner.
      T log10_aT = T(0.0);
      for (int k = o_.polynomial_degree; k >= 1; --k) log10_aT = (log10_aT + p[shift_index_ + k - 1]) * T(dT);
      shift_factor = exp(log10_aT * T(std::log(10.0)));
    }
    if (o_.vertical_shift)
      scale *= T(core::kelvin_from_celsius(c.temperature_C) / core::kelvin_from_celsius(o_.reference_C));
    if (o_.linear_factor) {
      T g = T(1.0) - p[factor_index_] * T(dT);
      if (value_of(g) < kMinLinearFactor) g = T(kMinLinearFactor);
      scale *= g;
    }
  }

  // Converts the native complex modulus (re, im) and relaxed modulus to the requested mode
  // through the constant bulk modulus K.
  template <typename T>
  void convert_mode(const T* p, TestMode to, T& re, T& im, T& relaxed) const {
    if (!o_.bulk_modulus)
      throw core::UsageError(std::string("a ") + to_string(o_.mode) + " card cannot answer a " +
                             to_string(to) + " test without a bulk modulus (option bulk_modulus)");
    const T K = p[k_index_];
    if (to == TestMode::bulk) {
      re = K;
      im = T(0.0);
      relaxed = K;
      return;
    }
    if (o_.mode == TestMode::bulk)
      throw core::UsageError("a bulk card cannot answer shear or uniaxial tests");
    auto divide = [](T ar, T ai, T br, T bi, T& qr, T& qi) {
      const T d = br * br + bi * bi;
      qr = (ar * br + ai * bi) / d;
      qi = (ai * br - ar * bi) / d;
    };
    if (to == TestMode::uniaxial) {  // E* = 9KG*/(3K + G*)
      divide(T(9.0) * K * re, T(9.0) * K * im, T(3.0) * K + re, im, re, im);
      relaxed = T(9.0) * K * relaxed / (T(3.0) * K + relaxed);
    } else {  // G* = 3KE*/(9K − E*)
      if (!(value_of(re) < 9.0 * value_of(K)))
        throw core::NumericalError("shear from uniaxial: E′ ≥ 9K, the bulk modulus is too small");
      divide(T(3.0) * K * re, T(3.0) * K * im, T(9.0) * K - re, -im, re, im);
      relaxed = T(3.0) * K * relaxed / (T(9.0) * K - relaxed);
    }
  }

  Options o_;
  std::vector<ParameterSpec> specs_;
  size_t kernel_size_ = 0, k_index_ = 0, shift_index_ = 0, factor_index_ = 0;
};

template <class Kernel>
ModelPtr make(const nlohmann::json& options) {
  return std::make_shared<LinearModel<Kernel>>(parse_options(options, Kernel::kHasTerms));
}

}  // namespace

bool is_linear_kind(const std::string& kind) {
  return kind == Prony::kKind || kind == Zener3::kKind || kind == Retardation::kKind ||
         kind == FractionalZener::kKind;
}

ModelPtr make_linear_model(const std::string& kind, const nlohmann::json& options) {
  if (kind == Prony::kKind) return make<Prony>(options);
  if (kind == Zener3::kKind) return make<Zener3>(options);
  if (kind == Retardation::kKind) return make<Retardation>(options);
  if (kind == FractionalZener::kKind) return make<FractionalZener>(options);
  throw core::UsageError("not a linear model kind: '" + kind + "'");
}

}  // namespace fitlib::model
