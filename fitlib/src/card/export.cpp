#include "fitlib/card/export.hpp"

#include "fitlib/card/conversion.hpp"
#include "fitlib/card/hyperelastic.hpp"
#include "export_text.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {
namespace {

// Ten significant digits keep every deck field within its format's limits (CalculiX 20 characters).
std::string num(double x) { return core::format_number(x, 10); }

// What every linear-FE format needs: relative Prony weights α_i = M_i/M_0 with times, the
// instantaneous Young's modulus and Poisson ratio, and how the weights apply to shear and bulk.
struct PronyExport {
  std::vector<double> alpha, tau_s;
  double young0_MPa = 0.0, shear0_MPa = 0.0, bulk_MPa = 0.0, poisson = 0.0;
  bool bulk_relaxes = false;  // uniaxial card: same α for bulk (constant Poisson ratio)
  bool from_retardation = false;  // the series is the card's retardation spectrum converted exactly
  double at_temperature_C = std::numeric_limits<double>::quiet_NaN();  // ExportOptions::temperature_C
  model::TemperatureFactors factors;                                     // the law's factors there
  // WLF shift log a_T = −C1 (T − T_ref)/(C2 + T − T_ref), when the card has one.
  bool wlf = false;
  double reference_C = 0.0, C1 = 0.0, C2_K = 0.0;
};

// Relative slack for values written at a bound (the card's decimal form of the bound).
constexpr double kBoundSlack = 1e-9;

}  // namespace

std::string admissibility_problems(const Card& card) {
  const auto values = card.values();
  model::MaxwellSeries s;
  if (!exact_maxwell_series(*card.model(), values, &s)) return {};
  std::ostringstream out;
  const double m0 = s.glassy();
  if (!(s.relaxed >= kMinRelaxedRatio * m0))
    out << "relaxed modulus " << num(s.relaxed) << " MPa is below " << kMinRelaxedRatio
        << " x the instantaneous " << num(m0) << " MPa; ";
  const nlohmann::json w = card.fit.value("admissible", nlohmann::json::object());
  if (!w.is_object() || w.empty()) return out.str();
  const double tau_lo = w.value("tau_min_s", 0.0), tau_hi = w.value("tau_max_s", INFINITY);
  const double ceiling = w.value("modulus_max_MPa", 0.0), floor = w.value("relaxed_min_MPa", 0.0);
  const double glassy_ceiling = w.value("glassy_modulus_max_MPa", 0.0);
  if (glassy_ceiling > 0.0 && m0 > glassy_ceiling * (1.0 + kBoundSlack))
    out << "instantaneous modulus " << num(m0) << " MPa above " << num(glassy_ceiling) << " MPa; ";
  // The window holds the model's own terms: a Prony card's τ_i and M_i, a retardation card's λ_i
  // (its converted relaxation times lie below them by nature).
  model::KelvinSeries k;
  const bool retardation = card.model()->kelvin_series(values.data(), &k);
  const std::vector<double>& times = retardation ? k.times_s : s.times_s;
  const std::vector<double>& weights = retardation ? k.compliances : s.moduli;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (weights[i] == 0.0) continue;  // a removed term
    if (times[i] < tau_lo * (1.0 - kBoundSlack) || times[i] > tau_hi * (1.0 + kBoundSlack))
      out << "term " << i + 1 << ": " << (retardation ? "lambda " : "tau ") << num(times[i]) << " s outside ["
          << num(tau_lo) << ", " << num(tau_hi) << "] s; ";
    if (!retardation && ceiling > 0.0 && s.moduli[i] > ceiling * (1.0 + kBoundSlack))
      out << "term " << i + 1 << ": modulus " << num(s.moduli[i]) << " MPa above " << num(ceiling) << " MPa; ";
  }
  if (floor > 0.0 && s.relaxed < floor * (1.0 - kBoundSlack))
    out << "relaxed modulus " << num(s.relaxed) << " MPa below " << num(floor) << " MPa; ";
  return out.str();
}

namespace {

// The route to a solver for a card Prony input cannot hold: its response where the part works,
// as a table, fitted by a Prony card (docs/cli.md "export").
constexpr const char* kPronyRoute =
    ": evaluate it where the part works and fit a Prony card to that, e.g. fitcli synth --card CARD "
    "--temperature-c T --amplitude A --frequency-hz F1,F2,... --out t.csv; fitcli fit --data t.csv --model prony "
    "--terms auto --out prony.json; then export prony.json";

PronyExport prepare(const Card& card, const std::string& format, const ExportOptions& o) {
  const auto m = card.model();
  const auto values = card.values();
  if (m->amplitude_dependent())
    throw core::UsageError(format + " Prony input cannot hold amplitude dependence (damage) of model '" +
                           card.model_kind + "'" + kPronyRoute);
  model::MaxwellSeries s;
  if (!exact_maxwell_series(*m, values, &s))
    throw core::UsageError("model '" + card.model_kind + "' is neither a Prony series nor a retardation spectrum; " +
                           format + " export needs one" + kPronyRoute);
  const int cap = max_prony_terms(format);
  if (cap > 0 && static_cast<int>(s.moduli.size()) > cap)
    throw core::UsageError(format + " accepts at most " + std::to_string(cap) + " Prony terms, the card has " +
                           std::to_string(s.moduli.size()) + " (refit with --max-terms " + std::to_string(cap) + ")");
  if (!o.allow_inadmissible) {
    const std::string problems = admissibility_problems(card);
    if (!problems.empty())
      throw core::UsageError("card '" + card.name + "' is not admissible for " + format + ": " + problems +
                             "refit, or pass --allow-inadmissible to export it anyway");
  }
  PronyExport e;
  if (std::isfinite(o.temperature_C)) {  // M(t, T) = b_T · M_ref(t / a_T): τ_i → a_T τ_i, M_i → b_T M_i
    require_material_at(card, card.name, o.temperature_C, "--temperature-c", "temperature_C");
    e.at_temperature_C = o.temperature_C;
    e.factors = m->temperature_factors(values.data(), o.temperature_C);
    for (double& t : s.times_s) t *= e.factors.shift_factor;
    for (double& g : s.moduli) g *= e.factors.scale;
    s.relaxed *= e.factors.scale;
  }
  const double m0 = s.glassy();
  model::MaxwellSeries own;
  e.from_retardation = !m->maxwell_series(values.data(), &own);
  for (size_t i = 0; i < s.moduli.size(); ++i) {
    if (s.moduli[i] < 0.0)
      throw core::UsageError(format + " needs non-negative Prony weights; term " + std::to_string(i + 1) +
                             " is negative (e.g. a three-parameter solid with tau_eps < tau_T)");
    e.alpha.push_back(s.moduli[i] / m0);
    e.tau_s.push_back(s.times_s[i]);
  }
  const model::TemperatureLawInfo law = m->temperature_law_info();
  const bool at_one_temperature = std::isfinite(e.at_temperature_C);
  // The route for a law the deck cannot hold: the card at the part's working temperature.
  const std::string route = ": export it at the part's working temperature (--temperature-c T: the terms' times "
                            "scaled by the card's shift factor there, valid at T only) or refit with --temperature-law wlf";
  if (!at_one_temperature && law.law != model::ShiftLaw::none && law.law != model::ShiftLaw::wlf)
    throw core::UsageError(format + " export supports only the WLF shift; the card uses '" +
                           m->temperature_law(values.data()).value("law", "?") + "'" + route);
  if (!at_one_temperature && (law.vertical_shift || law.linear_factor))
    throw core::UsageError(format + " Prony input cannot hold a vertical shift or a linear temperature factor" + route);
  if (!at_one_temperature && law.law == model::ShiftLaw::wlf) {
    e.wlf = true;
    e.reference_C = law.reference_C;
    e.C1 = values[law.shift_parameters.at(0)];
    e.C2_K = values[law.shift_parameters.at(1)];
  }
  const auto mode = m->native_mode();
  if (mode == model::TestMode::bulk) throw core::UsageError("a bulk card cannot be exported as a Prony material");
  const ElasticConstants c = elastic_constants(mode, m0, m->bulk_modulus(values.data()), o.poisson_ratio);
  e.young0_MPa = c.young0_MPa, e.shear0_MPa = c.shear0_MPa, e.bulk_MPa = c.bulk_MPa, e.poisson = c.poisson;
  e.bulk_relaxes = c.bulk_relaxes;
  return e;
}

}  // namespace

// `text` as comment lines of at most 80 characters (Abaqus reads 256 per line, LS-DYNA's cards 80).
std::string comment_lines(const char* comment, const std::string& text) {
  std::ostringstream out, line;
  std::istringstream words(text);
  std::string word;
  const std::size_t width = 80 - std::string(comment).size() - 1;
  while (words >> word) {
    if (line.tellp() > 0 && static_cast<std::size_t>(line.tellp()) + 1 + word.size() > width) {
      out << comment << " " << line.str() << "\n";
      line.str("");
    }
    line << (line.tellp() > 0 ? " " : "") << word;
  }
  if (line.tellp() > 0) out << comment << " " << line.str() << "\n";
  return out.str();
}

namespace {

std::string header(const Card& card, const char* comment, const PronyExport& e) {
  std::ostringstream out;
  out << comment_lines(comment, "fitlib export of card '" + card.name + "' (model " + card.model_kind + ", " +
                                    std::to_string(e.alpha.size()) + " Prony terms" +
                                    (e.from_retardation ? " converted exactly from its retardation spectrum" : "") +
                                    "); units MPa, s, degC");
  out << comment_lines(comment, e.bulk_relaxes
                                    ? "uniaxial card: the same relative weights relax shear and bulk (constant Poisson ratio)"
                                    : "shear card: bulk response elastic");
  if (std::isfinite(e.at_temperature_C))
    out << comment_lines(comment, "at " + num(e.at_temperature_C) + " degC only: times x " + num(e.factors.shift_factor) +
                                      " (shift factor a_T), moduli x " + num(e.factors.scale) + "; no temperature shift in this deck" +
                                      (card.model()->temperature_law_info().law == model::ShiftLaw::none
                                           ? " (the card has no temperature law: its terms as fitted)"
                                           : ""));
  if (const std::string q = fit_quality_warning(card); !q.empty()) out << comment_lines(comment, "WARNING: " + q);
  return out.str();
}

std::string abaqus(const Card& card, const PronyExport& e) {
  std::ostringstream out;
  out << header(card, "**", e);
  out << "*MATERIAL, NAME=" << (card.name.empty() ? "FITLIB" : card.name) << "\n";
  out << "*ELASTIC, MODULI=INSTANTANEOUS\n" << num(e.young0_MPa) << ", " << num(e.poisson) << "\n";
  out << "*VISCOELASTIC, TIME=PRONY\n";
  for (size_t i = 0; i < e.alpha.size(); ++i)
    out << num(e.alpha[i]) << ", " << num(e.bulk_relaxes ? e.alpha[i] : 0.0) << ", " << num(e.tau_s[i]) << "\n";
  if (e.wlf)
    out << "*TRS, DEFINITION=WLF\n" << num(e.reference_C) << ", " << num(e.C1) << ", " << num(e.C2_K) << "\n";
  return out.str();
}

void tbdata(std::ostringstream& out, const std::vector<double>& v) {
  for (size_t i = 0; i < v.size(); i += 6) {
    out << "TBDATA," << i + 1;
    for (size_t k = i; k < v.size() && k < i + 6; ++k) out << "," << num(v[k]);
    out << "\n";
  }
}

std::string ansys(const Card& card, const PronyExport& e, int id) {
  std::ostringstream out;
  out << header(card, "!", e);
  out << "MP,EX," << id << "," << num(e.young0_MPa) << "\n";
  out << "MP,PRXY," << id << "," << num(e.poisson) << "\n";
  std::vector<double> pairs;
  for (size_t i = 0; i < e.alpha.size(); ++i) {
    pairs.push_back(e.alpha[i]);
    pairs.push_back(e.tau_s[i]);
  }
  out << "TB,PRONY," << id << ",," << e.alpha.size() << ",SHEAR\n";
  tbdata(out, pairs);
  if (e.bulk_relaxes) {
    out << "TB,PRONY," << id << ",," << e.alpha.size() << ",BULK\n";
    tbdata(out, pairs);
  }
  if (e.wlf) {
    out << "TB,SHIFT," << id << ",,3,WLF\n";
    tbdata(out, {e.reference_C, e.C1, e.C2_K});
  }
  return out.str();
}

// *MAT_GENERAL_VISCOELASTIC (MAT_076), free format. LS-DYNA's convention (docs/formats.md §3
// "LS-DYNA"): G(t) = Σ GI e^(−BETAI t) and, when KI rows are given, K(t) = Σ KI e^(−BETAKI t);
// without KI rows the bulk response is elastic with BULK. The long-time moduli are rows with a
// zero decay constant; BULK, the elastic bulk modulus, is K(0). TREF, A, B: the WLF constants.
std::string lsdyna(const Card& card, const PronyExport& e, const ExportOptions& o) {
  if (o.density_t_per_mm3 == 0.0)
    throw core::UsageError("LS-DYNA needs the mass density RO (an explicit run stops at RO = 0) and "
                           "the card has none: pass --density in t/mm3 (rubber about 1.2e-9)");
  if (!(o.density_t_per_mm3 > 0.0) || !std::isfinite(o.density_t_per_mm3))
    throw core::UsageError("--density (LS-DYNA RO) must be a positive finite number of t/mm3, got " +
                           core::short_number(o.density_t_per_mm3));
  std::ostringstream out;
  out << header(card, "$", e);
  out << comment_lines("$", "K(t) = sum KI exp(-BETAKI t) (elastic BULK without KI rows); BULK = K(0); RO in t/mm3");
  out << "*MAT_GENERAL_VISCOELASTIC\n";
  out << "$ MID, RO, BULK, PCF, EF, TREF, A, B\n";
  out << o.material_id << "," << num(o.density_t_per_mm3) << "," << num(e.bulk_MPa) << ",0.0,0.0,"
      << (e.wlf ? num(e.reference_C) : "0.0") << "," << (e.wlf ? num(e.C1) : "0.0") << ","
      << (e.wlf ? num(e.C2_K) : "0.0") << "\n";
  out << "$ LCID, NT, BSTART, TRAMP, LCIDK, NTK, BSTARTK, TRAMPK\n0,0,0.0,0.0,0,0,0.0,0.0\n";
  out << "$ GI, BETAI, KI, BETAKI\n";
  double sum_alpha = 0.0;
  for (double a : e.alpha) sum_alpha += a;
  const double bulk_scale = e.bulk_relaxes ? e.bulk_MPa : 0.0;  // no KI rows: elastic BULK
  out << num(e.shear0_MPa * (1.0 - sum_alpha)) << ",0.0," << num(bulk_scale * (1.0 - sum_alpha))
      << ",0.0\n";
  for (size_t i = 0; i < e.alpha.size(); ++i)
    out << num(e.shear0_MPa * e.alpha[i]) << "," << num(1.0 / e.tau_s[i]) << ","
        << num(bulk_scale * e.alpha[i]) << "," << num(e.bulk_relaxes ? 1.0 / e.tau_s[i] : 0.0) << "\n";
  return out.str();
}

}  // namespace

int max_prony_terms(const std::string& format) {
  if (format == "lsdyna") return 5;  // six rows of MAT_076, one taken by the long-term modulus
  if (format == "ansys") return 100;
  return 0;
}

const std::vector<std::string>& export_formats() {
  static const std::vector<std::string> formats = {"abaqus", "ansys", "lsdyna"};
  return formats;
}

std::string export_card(const Card& card, const std::string& format, const ExportOptions& options) {
  // CalculiX has no built-in Prony viscoelasticity (it needs a user material): not a format.
  if (format != "abaqus" && format != "ansys" && format != "lsdyna")
    throw core::UsageError("unknown export format '" + format + "' (abaqus, ansys, lsdyna)");
  if (card.model()->hyperelastic()) return export_hyperelastic(card, format, options);
  const PronyExport e = prepare(card, format, options);
  if (format == "abaqus") return abaqus(card, e);
  if (format == "ansys") return ansys(card, e, options.material_id);
  return lsdyna(card, e, options);
}

}  // namespace fitlib::card
