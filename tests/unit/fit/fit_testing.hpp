#pragma once
// Shared helpers of the fit tests: synthetic tables from a model with known parameters and
// seeded noise, pyvisco files, and an independent Prony evaluation.
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/core/rng.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::fit::testing {

// `count` log-spaced frequencies from lo to hi (Hz).
inline std::vector<double> log_frequencies(double lo_Hz, double hi_Hz, int count) {
  std::vector<double> f(count);
  for (int i = 0; i < count; ++i)
    f[i] = count == 1 ? lo_Hz : lo_Hz * std::pow(hi_Hz / lo_Hz, double(i) / (count - 1));
  return f;
}

// Rows from `model` at `p`, storage and loss multiplied by (1 + noise·N(0,1)) each.
inline data::DynamicTestTable synthetic_table(const model::Model& model, const std::vector<double>& p,
                                              const std::vector<double>& frequencies_Hz,
                                              double relative_noise, std::uint64_t seed,
                                              model::TestMode mode = model::TestMode::shear,
                                              double temperature_C = std::nan("")) {
  core::Rng rng(seed);
  data::DynamicTestTable table;
  for (double f : frequencies_Hz) {
    data::DynamicTestRow row;
    row.condition.mode = mode;
    row.condition.frequency_Hz = f;
    row.condition.temperature_C = temperature_C;
    const auto m = model.moduli(p.data(), row.condition);
    row.storage_MPa = m.storage * (1.0 + relative_noise * rng.normal());
    row.loss_MPa = m.loss * (1.0 + relative_noise * rng.normal());
    table.rows.push_back(row);
  }
  return table;
}

inline model::ModelPtr prony(int terms, const std::string& mode = "shear") {
  return model::make_model("prony", {{"terms", terms}, {"mode", mode}});
}

// Prony parameters [M_inf, M_1..M_n, tau_1..tau_n].
inline std::vector<double> prony_parameters(double m_inf, const std::vector<double>& moduli,
                                            const std::vector<double>& times) {
  std::vector<double> p{m_inf};
  p.insert(p.end(), moduli.begin(), moduli.end());
  p.insert(p.end(), times.begin(), times.end());
  return p;
}

// pyvisco's example files, copied into the repository (datasets/materials, datasets/README.md).
inline std::string repo_path(const std::string& relative) {
  return std::string(FITLIB_SOURCE_DIR) + "/" + relative;
}

inline data::DynamicTestTable read_pyvisco(const std::string& relative) {
  data::ReadOptions o;
  o.format = data::TableFormat::pyvisco;
  o.has_default_mode = true;
  o.default_mode = model::TestMode::uniaxial;
  return data::read_dynamic_table(repo_path(relative), o);
}

// ANSYS TB,PRONY terms (α_i, τ_i) from an .MPL file.
inline std::vector<std::pair<double, double>> read_ansys_prony(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> values;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("TBDATA,", 0) != 0) continue;
    std::stringstream s(line.substr(7));
    std::string field;
    std::getline(s, field, ',');  // starting index
    while (std::getline(s, field, ',')) values.push_back(std::stod(field));
  }
  std::vector<std::pair<double, double>> terms;
  for (std::size_t k = 0; k + 1 < values.size(); k += 2) terms.emplace_back(values[k], values[k + 1]);
  return terms;
}

// Independent Prony evaluation in normalised form: E(ω) = E0[1 − Σα] + E0 Σ α iωτ/(1 + iωτ).
inline std::complex<double> normalised_prony(double e0, const std::vector<std::pair<double, double>>& terms,
                                             double omega) {
  double sum_alpha = 0.0;
  std::complex<double> e(0.0, 0.0);
  for (const auto& [alpha, tau] : terms) {
    sum_alpha += alpha;
    const std::complex<double> iwt(0.0, omega * tau);
    e += alpha * iwt / (1.0 + iwt);
  }
  return e0 * (1.0 - sum_alpha) + e0 * e;
}

}  // namespace fitlib::fit::testing
