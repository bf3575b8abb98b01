// The round trip is checked at fit time (issue 35, item 4): every card card::fit_card writes reads
// back through the checks of eval (card_from_json) and export (admissibility_problems), on the
// bundled tables as fitcli fit runs them: master curves from raw isotherms (pyvisco CSV, EPLEXOR
// raw .xls), an EPLEXOR master .xls, relaxation data, and --terms 1 … 40.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../fit/fit_testing.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/card/fit_card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/data/eplexor.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib {
namespace {

std::string dataset(const std::string& name) { return fit::testing::repo_path("datasets/materials/" + name); }

data::DynamicTestTable pyvisco_table(const std::string& name) {
  return fit::testing::read_pyvisco("datasets/materials/" + name);
}

card::FitCardOptions prony_options(const std::string& terms) {
  card::FitCardOptions o;
  o.model = "prony";
  o.terms = terms;
  o.model_options = {{"temperature_law", "none"}, {"reference_C", 23.0}};
  o.provenance = {"roundtrip", "test", false};
  return o;
}

// What eval and export say of a card written to JSON and read back: empty when both accept it.
std::string read_back(const card::Card& card) {
  try {
    return card::admissibility_problems(card::card_from_json(card::card_to_json(card)));
  } catch (const core::InputError& e) {
    return e.what();
  }
}

// fitcli fit --master-curve as cmd_fit runs it: pairwise shifts, refined with the spectrum for
// --terms auto, the card's WLF law fitted to them.
card::FitCardResult master_curve_card(const data::DynamicTestTable& raw, card::FitCardOptions o, double reference_C) {
  fit::MasterCurveOptions mo;
  mo.reference_C = reference_C;
  o.model_options["reference_C"] = reference_C;
  o.model_options["temperature_law"] = "wlf";
  const fit::MasterCurve curve = card::refine_master_curve(raw, fit::build_master_curve(raw, mo), o);
  card::IsothermShifts s;
  s.reference_C = curve.reference_C;
  for (const auto& iso : curve.isotherms) {
    s.temperatures_C.push_back(iso.temperature_C);
    s.log10_aT.push_back(iso.log10_aT);
  }
  o.shifts = s;
  o.provenance.measured = &raw;
  return card::fit_card(curve.master, o);
}

// Relaxation isotherms --master-curve as cmd_fit runs it.
card::FitCardResult relaxation_master_card(const data::RelaxationTable& raw, card::FitCardOptions o) {
  fit::MasterCurveOptions mo;
  mo.reference_C = 23.0;
  o.model_options["temperature_law"] = "wlf";
  const fit::MasterCurve curve = fit::build_relaxation_master_curve(raw, mo);
  const data::ShiftFactorTable given = fit::shift_factors_of(curve);
  const data::RelaxationTable table = fit::shift_relaxation_table(raw, given, 23.0);
  card::IsothermShifts s;
  s.reference_C = 23.0;
  for (const auto& f : given.factors) {
    s.temperatures_C.push_back(f.temperature_C);
    s.log10_aT.push_back(fit::given_log10_aT(given, f.temperature_C, 23.0));
  }
  o.shifts = s;
  o.measured_relaxation = &raw;
  return card::fit_relaxation_card(table, o);
}

// A law log10 a_T = −0.12 ΔT (Arrhenius-like, no curvature) drives the free WLF fit to C2 → ∞
// and C1 past the card's bound 1000; the bounded fit stays inside and still follows the shifts.
TEST(FitTimeRoundTrip, WlfFitIsTheBestFitInsideTheCardsBounds) {
  std::vector<double> t, a;
  for (double T = -20.0; T <= 60.0; T += 10.0) t.push_back(T), a.push_back(-0.12 * (T - 20.0));
  const fit::WlfFit free = fit::fit_wlf(t, a, 20.0);
  EXPECT_GT(free.C1, 1e3);
  const fit::WlfFit bounded = fit::fit_wlf(t, a, 20.0, 1e3, 1e4);
  EXPECT_LE(bounded.C1, 1e3);
  EXPECT_LE(bounded.C2_K, 1e4);
  EXPECT_LT(bounded.rms_decades, 0.05);
  // The same through the card's law: the model's bounds are applied and said.
  fit::FitResult r;
  r.model = model::make_model("prony", {{"terms", 1}});
  r.values = r.model->default_parameters();
  for (const auto& spec : r.model->parameters()) {
    fit::ParameterResult p;
    p.name = spec.name;
    p.unit = spec.unit;
    p.value = 1.0;
    r.parameters.push_back(p);
  }
  const fit::FitResult with = fit::with_law_from_shifts(r, t, a, 20.0, model::ShiftLaw::wlf);
  const auto info = with.model->temperature_law_info();
  EXPECT_LE(with.values[info.shift_parameters[0]], 1e3);
  bool said = false;
  for (const auto& m : with.messages) said = said || m.find("at its bound") != std::string::npos;
  EXPECT_TRUE(said);
}

// The reproduction: `fitcli fit --data pyvisco-freq-raw.csv --format pyvisco
// --master-curve --terms auto` wrote WLF C1 = 1131.75, which eval and export refuse.
TEST(FitTimeRoundTrip, RawIsothermsMasterCurveCardReadsBack) {
  const auto raw = pyvisco_table("pyvisco-freq-raw.csv");
  const card::FitCardResult r = master_curve_card(raw, prony_options("auto"), 23.0);
  EXPECT_EQ(read_back(r.card), "");
  const auto info = r.result.model->temperature_law_info();
  ASSERT_EQ(info.shift_parameters.size(), 2u);
  EXPECT_LE(r.result.values[info.shift_parameters[0]], 1e3);
}

TEST(FitTimeRoundTrip, EplexorRawAndMasterCardsReadBack) {
  const auto raw = data::read_eplexor(dataset("pyvisco-eplexor-raw.xls")).table;
  EXPECT_EQ(read_back(master_curve_card(raw, prony_options("auto"), 23.0).card), "");
  EXPECT_EQ(read_back(master_curve_card(raw, prony_options("8"), 23.0).card), "");
  for (const char* file : {"pyvisco-eplexor-master.xls", "pyvisco-eplexor-master-shear.xls"}) {
    const auto master = data::read_eplexor(dataset(file)).table;
    EXPECT_EQ(read_back(card::fit_card(master, prony_options("auto")).card), "") << file;
  }
}

// --terms 26 on pyvisco's master left E_inf below 1e-3 of the instantaneous modulus (export
// refused it): fit_card refits with the floor raised and says so.
TEST(FitTimeRoundTrip, RelaxedRatioBelowExportsIsRepairedAndSaid) {
  const auto master = pyvisco_table("pyvisco-freq-master.csv");
  const card::FitCardResult unchecked = card::fit_card_unchecked(master, prony_options("26"));
  const card::FitCardResult r = card::fit_card(master, prony_options("26"));
  EXPECT_EQ(read_back(r.card), "");
  model::MaxwellSeries s;
  ASSERT_TRUE(card::exact_maxwell_series(*r.card.model(), r.card.values(), &s));
  EXPECT_GE(s.relaxed, card::kMinRelaxedRatio * s.glassy());
  if (read_back(unchecked.card).empty()) return;  // the fit no longer needs the repair
  bool said = false;
  for (const auto& m : r.result.messages) said = said || m.find("floor raised") != std::string::npos;
  EXPECT_TRUE(said);
}

// Every --terms from 1 to 40 on pyvisco's master, and a spread of them on the other bundled
// tables: each card reads back, or the fit refuses with a NumericalError (exit 4).
TEST(FitTimeRoundTrip, EveryTermCountOnEveryBundledTableReadsBackOrRefuses) {
  const auto master = pyvisco_table("pyvisco-freq-master.csv");
  const auto raw = pyvisco_table("pyvisco-freq-raw.csv");
  const auto eplexor = data::read_eplexor(dataset("pyvisco-eplexor-master.xls")).table;
  const auto relaxation = data::read_relaxation_table(dataset("pyvisco-time-master.csv"));
  const auto relaxation_raw = data::read_relaxation_table(dataset("pyvisco-time-raw.csv"));
  int written = 0, refused = 0;
  const auto check = [&](const std::string& what, auto run) {
    try {
      const card::FitCardResult r = run();
      EXPECT_EQ(read_back(r.card), "") << what;
      ++written;
    } catch (const core::NumericalError& e) {
      ++refused;
      std::printf("%s: refused: %s\n", what.c_str(), e.what());
    }
  };
  for (int n = 1; n <= 40; ++n) {
    const std::string terms = std::to_string(n);
    check("master --terms " + terms, [&] { return card::fit_card(master, prony_options(terms)); });
    if (n % 7 != 1) continue;  // 1, 8, 15, 22, 29, 36 on the others
    check("raw --terms " + terms, [&] { return master_curve_card(raw, prony_options(terms), 23.0); });
    check("eplexor master --terms " + terms, [&] { return card::fit_card(eplexor, prony_options(terms)); });
    check("relaxation --terms " + terms, [&] { return card::fit_relaxation_card(relaxation, prony_options(terms)); });
    check("relaxation raw --terms " + terms, [&] { return relaxation_master_card(relaxation_raw, prony_options(terms)); });
  }
  check("relaxation --terms auto", [&] { return card::fit_relaxation_card(relaxation, prony_options("auto")); });
  check("relaxation raw --terms auto", [&] { return relaxation_master_card(relaxation_raw, prony_options("auto")); });
  EXPECT_GE(written, 60);
  std::printf("fit-time round trip: %d cards read back, %d fits refused\n", written, refused);
}

}  // namespace
}  // namespace fitlib
