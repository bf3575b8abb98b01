// Round trip is a law (issue 10, item 1): randomized fits over every model and option set;
// every card written reads back, evaluates to the fit's own curve bit for bit, holds only finite
// numbers, and keeps its series terms inside the admissible window it records.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fitlib/card/card.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/terms.hpp"

namespace fitlib {
namespace {

constexpr int kFits = 520;

// Every null in a card is a parameter's missing std_error (the documented form of "no interval").
void expect_only_documented_nulls(const nlohmann::json& j, const std::string& path, int& bad) {
  if (j.is_null()) {
    if (path.size() < 10 || path.compare(path.size() - 10, 10, ".std_error") != 0) {
      ADD_FAILURE() << "null at " << path;
      ++bad;
    }
    return;
  }
  if (j.is_number_float() && !std::isfinite(j.get<double>())) {
    ADD_FAILURE() << "non-finite at " << path;
    ++bad;
  }
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) expect_only_documented_nulls(*it, path + "." + it.key(), bad);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) expect_only_documented_nulls(j[i], path + "[" + std::to_string(i) + "]", bad);
}

struct Case {
  std::string kind;
  nlohmann::json options;
  bool auto_terms = false;  // --terms auto (smooth spectrum)
};

// A random model, option set and data table of known truth (the same family).
Case random_case(core::Rng& rng) {
  static const char* kinds[] = {"prony", "zener3", "retardation", "fractional-zener", "fritzson-iso"};
  static const char* laws[] = {"none", "wlf", "arrhenius"};
  Case c;
  c.kind = kinds[static_cast<int>(rng.uniform() * 5.0) % 5];
  const bool uniaxial = rng.uniform() < 0.5;
  if (c.kind == "fritzson-iso") {
    c.options = {{"reference_C", 23.0}};
    return c;
  }
  c.options = {{"mode", uniaxial ? "uniaxial" : "shear"},
               {"temperature_law", laws[static_cast<int>(rng.uniform() * 3.0) % 3]},
               {"reference_C", 23.0}};
  if (c.kind == "prony" || c.kind == "retardation") {
    c.options["terms"] = 1 + static_cast<int>(rng.uniform() * 4.0) % 4;
    c.auto_terms = c.kind == "prony" && c.options["temperature_law"] == "none" && rng.uniform() < 0.3;
  }
  return c;
}

data::DynamicTestTable random_table(const model::Model& truth, const std::vector<double>& p, core::Rng& rng,
                                    bool temperatures, bool amplitudes) {
  data::DynamicTestTable table;
  const int points = 6 + static_cast<int>(rng.uniform() * 8.0);
  const double lo = std::pow(10.0, -2.0 + 2.0 * rng.uniform()), decades = 1.0 + 4.0 * rng.uniform();
  const double noise = rng.uniform() < 0.3 ? 0.0 : 0.03 * rng.uniform();
  const std::vector<double> temps = temperatures ? std::vector<double>{0.0, 23.0, 50.0} : std::vector<double>{23.0};
  int line = 0;
  for (double t : temps)
    for (int k = 0; k < points; ++k) {
      data::DynamicTestRow row;
      row.condition.mode = truth.native_mode();
      row.condition.frequency_Hz = lo * std::pow(10.0, decades * k / std::max(points - 1, 1));
      row.condition.temperature_C = t;
      if (amplitudes) row.condition.strain_amplitude = 0.01 + 0.1 * (k % 3);
      const auto m = truth.moduli(p.data(), row.condition);
      row.storage_MPa = m.storage * (1.0 + noise * rng.normal());
      row.loss_MPa = std::max(m.loss * (1.0 + noise * rng.normal()), 0.0);
      row.source_file = "synthetic";
      row.source_line = ++line;
      table.rows.push_back(row);
    }
  table.source_files = {"synthetic"};
  table.source_sha256 = {"0"};
  return table;
}

fit::FitOptions random_options(core::Rng& rng) {
  static const fit::Backend backends[] = {fit::Backend::automatic, fit::Backend::nnls, fit::Backend::ceres,
                                          fit::Backend::nlopt};
  static const fit::ResidualKind residuals[] = {fit::ResidualKind::log10, fit::ResidualKind::relative,
                                                fit::ResidualKind::complex};
  fit::FitOptions o;
  o.backend = backends[static_cast<int>(rng.uniform() * 4.0) % 4];
  o.residual = residuals[static_cast<int>(rng.uniform() * 3.0) % 3];
  o.storage_weight = std::pow(10.0, 2.0 * rng.uniform());
  o.loss_weight = std::pow(10.0, rng.uniform() - 0.5);
  o.max_iterations = 30;
  o.multistart = 2;
  o.seed = static_cast<std::uint64_t>(1 + 1000 * rng.uniform());
  return o;
}

TEST(RoundTripProperty, EveryCardReadsBackAndEvaluatesToItsFit) {
  core::Rng rng(20261124);
  int written = 0, failed_fits = 0, outside_window = 0, bad_values = 0, mismatches = 0;
  std::map<std::string, int> per_kind;
  for (int i = 0; i < kFits; ++i) {
    const Case c = random_case(rng);
    const auto truth = model::make_model(c.kind, c.options);
    std::vector<double> p = truth->default_parameters();
    const bool law = c.options.value("temperature_law", std::string("none")) != "none";
    const auto table = random_table(*truth, p, rng, law, c.kind == "fritzson-iso");
    fit::FitOptions o = random_options(rng);
    if (c.kind == "fritzson-iso") o.backend = fit::Backend::automatic;
    fit::FitResult r;
    try {
      if (c.auto_terms) {
        fit::TermOptions t;
        nlohmann::json opts = c.options;
        opts.erase("terms");
        r = fit::select_terms(c.kind, opts, table, o, t).result;
      } else {
        r = fit::fit(truth, table, o);
      }
    } catch (const core::NumericalError&) {
      ++failed_fits;  // a fit may fail; it must fail with a NumericalError and write nothing
      continue;
    }
    const auto card = card::card_from_fit(r, o, table, {"case-" + std::to_string(i), "property test", false});
    const std::string path = fitlib_test::temp_path("card-" + std::to_string(i) + ".json");
    card::save_card(path, card);
    card::Card back;
    ASSERT_NO_THROW(back = card::load_card(path)) << "case " << i << " " << c.kind << " " << c.options.dump();
    ++written;
    ++per_kind[c.kind];
    expect_only_documented_nulls(card::card_to_json(back), "card", bad_values);
    const auto model = back.model();
    const auto values = back.values();
    for (const auto& row : table.rows) {
      for (double scale : {1.0, 0.37, 3.1}) {
        model::TestCondition cond = row.condition;
        cond.frequency_Hz *= scale;
        const auto a = r.model->moduli(r.values.data(), cond);
        const auto b = model->moduli(values.data(), cond);
        if (!(a.storage == b.storage && a.loss == b.loss && std::isfinite(b.storage) && std::isfinite(b.loss))) {
          ++mismatches;
          ADD_FAILURE() << "case " << i << " " << c.kind << ": eval of the card differs from the fit at "
                        << cond.frequency_Hz << " Hz";
        }
      }
    }
    const std::string problems = card::admissibility_problems(back);
    if (r.admissible.applies && !problems.empty()) {
      ++outside_window;
      ADD_FAILURE() << "case " << i << " " << c.kind << " " << c.options.dump() << ": " << problems;
    }
  }
  EXPECT_GE(written, 500);
  EXPECT_LE(failed_fits, kFits / 20);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(outside_window, 0);
  EXPECT_EQ(bad_values, 0);
  for (const char* kind : {"prony", "zener3", "retardation", "fractional-zener", "fritzson-iso"})
    EXPECT_GE(per_kind[kind], 50) << kind;
  std::printf("round trip: %d cards, %d fits failed (NumericalError)\n", written, failed_fits);
}

}  // namespace
}  // namespace fitlib
