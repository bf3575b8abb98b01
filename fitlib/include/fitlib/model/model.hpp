#pragma once
// The one interface every constitutive law offers. The fitter, the card writer and the segment
// solver use only this; none of them switches on a model's name.
//
// A model is a description (parameter specs, options) plus pure functions of a parameter vector
// `p` in natural units (MPa, s, ...). Fitters handle transforms (log for positive scales).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "fitlib/core/parameter.hpp"
#include "fitlib/model/test_condition.hpp"

namespace fitlib::model {

// Moduli of a steady sinusoidal test, MPa: storage (dynamic elastic) E′ or G′, loss E″ or G″,
// and the mean (static) modulus = mean stress / mean strain.
template <typename T>
struct Moduli {
  T storage;
  T loss;
  T mean;
};

// Strain history sampled at times t_s (strictly increasing, t_s[0] = start, material at rest
// before it). Strain is engineering strain of the test mode (shear: γ).
struct StrainHistory {
  std::vector<double> time_s;
  std::vector<double> strain;
};

// Throws core::UsageError unless time and strain have equal lengths and times increase strictly.
void check_strain_history(const StrainHistory& history);

// What a fitter knows about the data before fitting, for models to place a sensible start.
struct DataSummary {
  double omega_min_rad_s = 1.0, omega_max_rad_s = 1.0;  // angular frequency range
  double storage_min_MPa = 1.0, storage_max_MPa = 1.0;
  double loss_max_MPa = 0.0;
  double temperature_min_C = 23.0, temperature_max_C = 23.0;
};

struct MaxwellSeries;   // time_series.hpp
struct KelvinSeries;    // time_series.hpp
struct PointOptions;    // material_point.hpp
class MaterialPoint;    // material_point.hpp
class HyperelasticLaw;  // hyperelastic.hpp

// The horizontal temperature law of a model, as typed data for fitters and exports.
enum class ShiftLaw { none, wlf, arrhenius, polynomial, other };
// The option value of a law ("none", "wlf", "arrhenius", "polynomial"; "other" has none) and
// back (core::UsageError for an unknown name; for user input and the options JSON).
std::string to_string(ShiftLaw law);
// Model::temperature_out_of_law's text for a linear factor g = 1 − c (T − T_ref) (parameter
// `name`) at or below `floor`, "" above it.
std::string linear_factor_out_of_law(const std::string& name, double c_per_C, double reference_C,
                                     double temperature_C, double floor);
ShiftLaw parse_shift_law(const std::string& name);
struct TemperatureLawInfo {
  ShiftLaw law = ShiftLaw::none;
  double reference_C = 23.0;
  // Indices of the law's constants in the law's order (WLF: C1, C2; Arrhenius: E_a;
  // polynomial: C_1 … C_degree).
  std::vector<int> shift_parameters;
  // The parameter p_k that places the law's pole at reference_C − p_k (WLF: C2); −1 = no pole.
  int pole_parameter = -1;
  bool vertical_shift = false;       // entropic factor T/T_ref
  bool linear_factor = false;        // g(T) = 1 − c_T (T − T_ref)
};

// Temperature factors at one temperature: reduced frequency ω·shift_factor (reduced time
// t/shift_factor) and moduli scaled by `scale`.
struct TemperatureFactors {
  double shift_factor = 1.0;
  double scale = 1.0;
};

class Model {
 public:
  virtual ~Model() = default;

  // Name used by --model and in cards ("prony", "zener3", ...).
  virtual std::string kind() const = 0;
  virtual const std::vector<core::ParameterSpec>& parameters() const = 0;
  std::size_t size() const { return parameters().size(); }

  // Model options that define its structure (term count, temperature law, ...), as stored in a
  // card's "options" object; make_model(kind, options) rebuilds the same model.
  virtual nlohmann::json options() const = 0;

  // Complex-form moduli at one test condition.
  virtual Moduli<double> moduli(const double* p, const TestCondition& c) const = 0;

  // Same, with derivatives d(storage, loss, mean)/dp as a 3 × size() matrix.
  virtual Moduli<double> moduli(const double* p, const TestCondition& c,
                                Eigen::Ref<Eigen::MatrixXd> jacobian) const = 0;

  // Stress history (MPa) for the imposed strain history, in the mode and at the temperature of
  // `c` (its frequency and amplitude are ignored). The discretisation is the model's own and
  // exact for piecewise-linear strain where the model allows it.
  virtual std::vector<double> stress_response(const double* p, const TestCondition& c,
                                              const StrainHistory& history) const = 0;

  // Relaxation modulus M(t) (MPa) after a unit strain step, and creep compliance J(t) (1/MPa)
  // after a unit stress step, at the mode and temperature of `c`.
  virtual double relaxation_modulus(const double* p, const TestCondition& c, double t_s) const = 0;
  virtual double creep_compliance(const double* p, const TestCondition& c, double t_s) const = 0;

  // Capabilities that FE exports read (they refuse what a format cannot hold):
  // the mode whose moduli the model describes natively (a shear card, a uniaxial card, ...);
  virtual TestMode native_mode() const = 0;
  // the model as an exact generalized Maxwell series at the reference temperature, if it is one;
  virtual bool maxwell_series(const double* p, MaxwellSeries* out) const { return false; }
  // the temperature law and its constants: {"law": "none|wlf|arrhenius|...", "reference_C": …};
  virtual nlohmann::json temperature_law(const double* p) const;
  // true when moduli depend on strain amplitude (damage): linear FE formats cannot hold it.
  virtual bool amplitude_dependent() const { return false; }
  // the damage drivers (the amplitudes its damage functions read, in the model's order) that a
  // steady dynamic test at `c` reaches with parameters p; empty for a model without damage;
  virtual std::vector<double> damage_drivers(const double* p, const TestCondition& c) const { return {}; }
  // the model as an exact Kelvin chain (discrete retardation spectrum), if it is one;
  virtual bool kelvin_series(const double* p, KelvinSeries* out) const { return false; }
  // its constant (elastic) bulk modulus K in MPa, if it has one; NaN otherwise;
  virtual double bulk_modulus(const double* p) const;
  // the temperature law as typed data (no name lookups outside model);
  virtual TemperatureLawInfo temperature_law_info() const { return {}; }
  // the temperature factors at T (°C; NaN = reference);
  virtual TemperatureFactors temperature_factors(const double* p, double temperature_C) const {
    return {};
  }
  // why the temperature law describes no material at T (°C), "" where it does (and at NaN):
  // at or beyond a WLF pole, or where a linear factor g = 1 − c (T − T_ref) has reached the floor
  // that keeps a fitter's iterates finite. A card is not evaluated there (card::require_material_at);
  virtual std::string temperature_out_of_law(const double* p, double temperature_C) const { return {}; }

  // The material point of this model with parameters p (material_point.hpp): the one call from
  // a card to what an FE code drives. Every model of make_model implements it (the default
  // throws core::UsageError, for models built elsewhere, e.g. a fitter's internal models).
  virtual std::shared_ptr<const MaterialPoint> material_point(const double* p,
                                                             const PointOptions& options) const;

  // The large-strain elastic law of a hyperelastic model (nominal stress per quasi-static test
  // mode, its typed form for exports); null for the others.
  virtual const HyperelasticLaw* hyperelastic() const { return nullptr; }

  // Default values of all parameters (a start for fitting, a sane demo card).
  std::vector<double> default_parameters() const;

  // A start for fitting placed from the data (e.g. a log-spaced τ grid over the measured
  // frequencies). The default returns default_parameters().
  virtual std::vector<double> initial_parameters(const DataSummary& data) const;
};

using ModelPtr = std::shared_ptr<const Model>;

// Builds a model by name with its options (e.g. {"terms": 12}, {"temperature_law": "wlf"}).
// Throws core::UsageError for an unknown name or option.
ModelPtr make_model(const std::string& kind, const nlohmann::json& options);

// core::UsageError "KIND: parameter 'NAME' is not finite" for the first non-finite value of p (the
// model's parameters, in order): checked where values enter from a user, not on the fit's hot path.
void require_finite_parameters(const Model& model, const std::vector<double>& p);

// The names make_model accepts (the built-in ones, then the registered ones).
std::vector<std::string> model_kinds();

// A model defined outside the library joins make_model and model_kinds (and so cards, fits,
// exports and points) with one call; core::UsageError when the name is taken.
using ModelFactory = std::function<ModelPtr(const nlohmann::json& options)>;
void register_model(const std::string& kind, ModelFactory factory);

}  // namespace fitlib::model
