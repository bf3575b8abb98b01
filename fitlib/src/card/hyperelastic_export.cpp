// FE keywords of a hyperelastic card (card/hyperelastic.hpp; conventions: docs/hyperelastic.md
// §"Exports"). Abaqus and CalculiX read the Abaqus forms the card stores; ANSYS and LS-DYNA write
// Ogden as Σ μ_i/α_i (…), so their μ_i = 2 μ_i(Abaqus)/α_i (the initial shear modulus
// μ0 = Σ μ_i(Abaqus) = ½ Σ α_i μ_i(ANSYS)).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "export_text.hpp"
#include "fitlib/card/hyperelastic.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {
namespace {

using model::HyperelasticFamily;
using model::HyperelasticForm;

std::string num(double x) { return core::format_number(x, 10); }

// Values as comma lists of at most `per_line` per line.
std::string data_lines(const std::vector<double>& v, std::size_t per_line, const std::string& lead = "") {
  std::ostringstream out;
  for (std::size_t i = 0; i < v.size(); i += per_line) {
    out << lead;
    for (std::size_t k = i; k < v.size() && k < i + per_line; ++k) out << (k > i || !lead.empty() ? "," : "") << num(v[k]);
    out << "\n";
  }
  return out.str();
}

double coefficient(const HyperelasticForm& f, int i, int j) {
  for (const auto& c : f.coefficients)
    if (c.i == i && c.j == j) return c.value_MPa;
  return 0.0;
}

// D1 of the deck: the card's, or 2/K with K from the Poisson ratio and μ0 (incompressible card).
struct Volumetric {
  double D1 = 0.0, bulk_MPa = 0.0, poisson = 0.0;
  bool from_poisson = false;
};
Volumetric volumetric(const HyperelasticForm& f, double poisson) {
  Volumetric v;
  const double G = f.initial_shear_modulus_MPa;
  if (f.D1_per_MPa > 0.0) {
    v.D1 = f.D1_per_MPa, v.bulk_MPa = 2.0 / v.D1;
    v.poisson = (3.0 * v.bulk_MPa - 2.0 * G) / (2.0 * (3.0 * v.bulk_MPa + G));
    return v;
  }
  v.from_poisson = true, v.poisson = poisson;
  v.bulk_MPa = 2.0 * G * (1.0 + poisson) / (3.0 * (1.0 - 2.0 * poisson));
  v.D1 = 2.0 / v.bulk_MPa;
  return v;
}

std::string header(const Card& card, const char* comment, const Volumetric& v, const std::string& convention) {
  std::ostringstream out;
  out << comment_lines(comment, "fitlib export of hyperelastic card '" + card.name + "' (model " + card.model_kind +
                                    "); units MPa; " + convention);
  out << comment_lines(comment, v.from_poisson ? "incompressible card: D1 = 2/K with K = " + num(v.bulk_MPa) +
                                                     " MPa from Poisson ratio " + num(v.poisson) + " and mu0"
                                               : "D1 = " + num(v.D1) + " 1/MPa from the card (K0 = 2/D1)");
  if (const std::string q = fit_quality_warning(card); !q.empty()) out << comment_lines(comment, "WARNING: " + q);
  return out.str();
}

std::string material_name(const Card& card) { return card.name.empty() ? "FITLIB" : card.name; }

std::string abaqus(const Card& card, const HyperelasticForm& f, const Volumetric& v) {
  std::string option;
  std::vector<double> values;
  const auto d_terms = [&](int n) {
    values.push_back(v.D1);
    for (int k = 1; k < n; ++k) values.push_back(0.0);
  };
  switch (f.family) {
    case HyperelasticFamily::neo_hooke: option = "NEO HOOKE", values = {coefficient(f, 1, 0)}, d_terms(1); break;
    case HyperelasticFamily::mooney_rivlin:
      if (f.order == 1) {
        option = "MOONEY-RIVLIN", values = {coefficient(f, 1, 0), coefficient(f, 0, 1)}, d_terms(1);
      } else {  // C10, C01, C20, C11, C02
        option = "POLYNOMIAL, N=2";
        values = {coefficient(f, 1, 0), coefficient(f, 0, 1), 0.0, coefficient(f, 1, 1), 0.0};
        d_terms(2);
      }
      break;
    case HyperelasticFamily::yeoh:
    case HyperelasticFamily::reduced_polynomial:
      option = f.family == HyperelasticFamily::yeoh ? "YEOH" : "REDUCED POLYNOMIAL, N=" + std::to_string(f.order);
      for (int i = 1; i <= f.order; ++i) values.push_back(coefficient(f, i, 0));
      d_terms(f.order);
      break;
    case HyperelasticFamily::ogden:
      option = "OGDEN, N=" + std::to_string(f.order);
      for (int k = 0; k < f.order; ++k) values.push_back(f.mu_MPa[k]), values.push_back(f.alpha[k]);
      d_terms(f.order);
      break;
    case HyperelasticFamily::arruda_boyce: option = "ARRUDA-BOYCE", values = {f.mu_MPa[0], f.lambda_m}, d_terms(1); break;
    case HyperelasticFamily::gent:
      throw core::UsageError("abaqus: *HYPERELASTIC has no Gent form (export a gent card with --format ansys, "
                             "or fit arruda-boyce)");
  }
  std::ostringstream out;
  out << header(card, "**", v,
                "Abaqus forms as in the card (Ogden: W = sum 2 mu_i/alpha_i^2 (...), mu0 = sum mu_i); "
                "CalculiX reads the same keyword for N <= 3");
  out << "*MATERIAL, NAME=" << material_name(card) << "\n";
  out << "*HYPERELASTIC, " << option << "\n" << data_lines(values, 8);
  return out.str();
}

std::string ansys(const Card& card, const HyperelasticForm& f, const Volumetric& v, int id) {
  std::ostringstream tb;
  std::vector<double> values;
  const std::string m = std::to_string(id);
  switch (f.family) {
    case HyperelasticFamily::neo_hooke: tb << "TB,HYPER," << m << ",,,NEO", values = {2.0 * coefficient(f, 1, 0), v.D1}; break;
    case HyperelasticFamily::mooney_rivlin:
      tb << "TB,HYPER," << m << ",," << (f.order == 1 ? 2 : 3) << ",MOONEY";
      values = {coefficient(f, 1, 0), coefficient(f, 0, 1)};
      if (f.order == 2) values.push_back(coefficient(f, 1, 1));
      values.push_back(v.D1);
      break;
    case HyperelasticFamily::yeoh:
    case HyperelasticFamily::reduced_polynomial:
      tb << "TB,HYPER," << m << ",," << f.order << ",YEOH";
      for (int i = 1; i <= f.order; ++i) values.push_back(coefficient(f, i, 0));
      values.push_back(v.D1);
      for (int i = 1; i < f.order; ++i) values.push_back(0.0);
      break;
    case HyperelasticFamily::ogden:
      tb << "TB,HYPER," << m << ",," << f.order << ",OGDEN";
      for (int k = 0; k < f.order; ++k) values.push_back(2.0 * f.mu_MPa[k] / f.alpha[k]), values.push_back(f.alpha[k]);
      values.push_back(v.D1);
      for (int k = 1; k < f.order; ++k) values.push_back(0.0);
      break;
    case HyperelasticFamily::arruda_boyce: tb << "TB,HYPER," << m << ",,,BOYCE", values = {f.mu_MPa[0], f.lambda_m, v.D1}; break;
    case HyperelasticFamily::gent: tb << "TB,HYPER," << m << ",,,GENT", values = {f.mu_MPa[0], f.J_m, v.D1}; break;
  }
  std::ostringstream out;
  out << header(card, "!", v,
                "ANSYS forms: NEO mu = 2 C10; OGDEN W = sum mu_i/alpha_i (...), mu_i = 2 mu_i(Abaqus)/alpha_i; "
                "d = D1 (GENT: ANSYS's volumetric term (J^2-1)/2 - ln J with the same K0 = 2/d)");
  out << tb.str() << "\n";
  for (std::size_t i = 0; i < values.size(); i += 6)  // TBDATA's first field: the starting location
    out << data_lines(std::vector<double>(values.begin() + i, values.begin() + std::min(values.size(), i + 6)), 6,
                      "TBDATA," + std::to_string(i + 1));
  return out.str();
}

std::string lsdyna(const Card& card, const HyperelasticForm& f, const Volumetric& v, const ExportOptions& o) {
  if (!(o.density_t_per_mm3 > 0.0) || !std::isfinite(o.density_t_per_mm3))
    throw core::UsageError("LS-DYNA needs the mass density RO (an explicit run stops at RO = 0) and "
                           "the card has none: pass --density in t/mm3 (rubber about 1.2e-9)");
  std::ostringstream out;
  const std::string id = std::to_string(o.material_id), ro = num(o.density_t_per_mm3), pr = num(v.poisson);
  if (f.family == HyperelasticFamily::ogden) {
    if (f.order > 8) throw core::UsageError("lsdyna: *MAT_OGDEN_RUBBER holds at most 8 Ogden terms");
    out << header(card, "$", v, "MAT_077_O: W = sum mu_i/alpha_i (...), mu_i = 2 mu_i(Abaqus)/alpha_i; PR from K0 = 2/D1");
    out << "*MAT_OGDEN_RUBBER\n$ MID, RO, PR, N, NV, G, SIGF, REF\n" << id << "," << ro << "," << pr << ",0,0,0.0,0.0,0.0\n";
    std::vector<double> mu(8, 0.0), alpha(8, 0.0);
    for (int k = 0; k < f.order; ++k) mu[k] = 2.0 * f.mu_MPa[k] / f.alpha[k], alpha[k] = f.alpha[k];
    out << "$ MU1 ... MU8\n" << data_lines(mu, 8) << "$ ALPHA1 ... ALPHA8\n" << data_lines(alpha, 8);
    return out.str();
  }
  const bool polynomial = f.family == HyperelasticFamily::neo_hooke || f.family == HyperelasticFamily::mooney_rivlin ||
                          f.family == HyperelasticFamily::yeoh || f.family == HyperelasticFamily::reduced_polynomial;
  if (!polynomial) throw core::UsageError("lsdyna: no built-in keyword holds " + card.model_kind + " (export it for abaqus or ansys)");
  if (f.family == HyperelasticFamily::neo_hooke || (f.family == HyperelasticFamily::mooney_rivlin && f.order == 1)) {
    out << header(card, "$", v, "MAT_027: A = C10, B = C01; PR from K0 = 2/D1");
    out << "*MAT_MOONEY-RIVLIN_RUBBER\n$ MID, RO, PR, A, B, REF\n" << id << "," << ro << "," << pr << ","
        << num(coefficient(f, 1, 0)) << "," << num(coefficient(f, 0, 1)) << ",0.0\n$ SGL, SW, ST, LCID\n0.0,0.0,0.0,0\n";
    return out.str();
  }
  for (const auto& c : f.coefficients)
    if (c.i + c.j > 3 && c.value_MPa != 0.0)
      throw core::UsageError("lsdyna: *MAT_HYPERELASTIC_RUBBER holds C10, C01, C11, C20, C02, C30 only; the card has C" +
                             std::to_string(c.i) + std::to_string(c.j));
  out << header(card, "$", v, "MAT_077_H: polynomial C_ij as in the card; PR from K0 = 2/D1");
  out << "*MAT_HYPERELASTIC_RUBBER\n$ MID, RO, PR, N, NV, G, SIGF, REF\n" << id << "," << ro << "," << pr
      << ",0,0,0.0,0.0,0.0\n$ C10, C01, C11, C20, C02, C30\n"
      << data_lines({coefficient(f, 1, 0), coefficient(f, 0, 1), coefficient(f, 1, 1), coefficient(f, 2, 0),
                     coefficient(f, 0, 2), coefficient(f, 3, 0)},
                    8);
  return out.str();
}

}  // namespace

std::string export_hyperelastic(const Card& card, const std::string& format, const ExportOptions& options) {
  const auto m = card.model();
  const auto values = card.values();
  const HyperelasticForm f = m->hyperelastic()->form(values.data());
  if (!(f.initial_shear_modulus_MPa > 0.0))
    throw core::UsageError("the card's initial shear modulus " + num(f.initial_shear_modulus_MPa) +
                           " MPa is not > 0: no FE code accepts it");
  const Volumetric v = volumetric(f, options.poisson_ratio);
  model::MaxwellSeries prony;
  if (m->maxwell_series(values.data(), &prony)) {  // visco-hyperelastic: the base is the long-term response
    if (format != "abaqus")
      throw core::UsageError(format + ": a visco-hyperelastic card is written for abaqus only (its base as "
                             "*HYPERELASTIC, MODULI=LONG TERM with *VISCOELASTIC, TIME=PRONY)");
    std::string deck = abaqus(card, f, v);
    const auto at = deck.find("\n", deck.find("*HYPERELASTIC, "));
    deck.insert(at, ", MODULI=LONG TERM");
    deck += "*VISCOELASTIC, TIME=PRONY\n";
    for (std::size_t i = 0; i < prony.moduli.size(); ++i)  // g_i, k_i = 0 (bulk elastic), tau_i
      deck += num(prony.moduli[i] / prony.glassy()) + ",0," + num(prony.times_s[i]) + "\n";
    return deck;
  }
  if (format == "abaqus") return abaqus(card, f, v);
  if (format == "ansys") return ansys(card, f, v, options.material_id);
  if (format == "lsdyna") return lsdyna(card, f, v, options);
  throw core::UsageError("unknown export format '" + format + "'");
}

}  // namespace fitlib::card
