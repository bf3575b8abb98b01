#include "fitlib/card/conversion.hpp"

#include <cmath>
#include <complex>

#include "fitlib/core/error.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {

ElasticConstants elastic_constants(model::TestMode native, double m0, double bulk, double nu) {
  const bool has_bulk = !std::isnan(bulk);
  ElasticConstants e;
  if (native == model::TestMode::bulk) throw core::UsageError("a bulk card cannot answer shear or uniaxial tests");
  if (native == model::TestMode::shear) {
    e.shear0_MPa = m0;
    e.bulk_MPa = has_bulk ? bulk : 2.0 * m0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
    e.young0_MPa = 9.0 * e.bulk_MPa * m0 / (3.0 * e.bulk_MPa + m0);
  } else {
    e.young0_MPa = m0;
    e.bulk_MPa = has_bulk ? bulk : m0 / (3.0 * (1.0 - 2.0 * nu));
    e.shear0_MPa = 3.0 * e.bulk_MPa * m0 / (9.0 * e.bulk_MPa - m0);
    e.bulk_relaxes = !has_bulk;
  }
  e.poisson = (3.0 * e.bulk_MPa - 2.0 * e.shear0_MPa) / (2.0 * (3.0 * e.bulk_MPa + e.shear0_MPa));
  return e;
}

namespace {

// Native complex modulus M* → the same material's modulus in mode `to` (shear card: elastic K;
// uniaxial card: constant ν, so G* = E*/(2(1 + ν)) and K* = E*/(3(1 − 2ν))).
std::complex<double> convert(std::complex<double> M, model::TestMode native, model::TestMode to,
                             const ElasticConstants& e) {
  if (native == model::TestMode::shear)
    return to == model::TestMode::bulk ? std::complex<double>(e.bulk_MPa, 0.0) : 9.0 * e.bulk_MPa * M / (3.0 * e.bulk_MPa + M);
  const double nu = e.poisson;
  return to == model::TestMode::shear ? M / (2.0 * (1.0 + nu)) : M / (3.0 * (1.0 - 2.0 * nu));
}

}  // namespace

namespace {

// The native instantaneous modulus the conversion starts from: a series' glassy modulus; a shear
// card's relaxation modulus at t = 0 (its glassy limit: 1/J_g of a retardation spectrum, G_0 + ΔG
// of a fractional Zener card); a uniaxial card's storage modulus `storage` at the condition (its ν
// does not depend on it).
double instantaneous_MPa(const model::Model& model, const std::vector<double>& p, const model::TestCondition& c,
                         double storage, model::TestMode asked) {
  model::MaxwellSeries s;
  if (exact_maxwell_series(model, p, &s)) return s.glassy();
  if (model.native_mode() != model::TestMode::shear) return storage;
  model::TestCondition reference = c;  // K does not follow the temperature (as a series' glassy one)
  reference.temperature_C = std::nan("");
  const double glassy = model.relaxation_modulus(p.data(), reference, 0.0);
  if (std::isfinite(glassy) && glassy > 0.0) return glassy;
  throw core::UsageError("a shear card without a finite instantaneous modulus cannot answer a " +
                         std::string(model::to_string(asked)) + " test without a bulk modulus (fit with --bulk-modulus)");
}

}  // namespace

bool exact_maxwell_series(const model::Model& model, const std::vector<double>& values, model::MaxwellSeries* out) {
  if (model.maxwell_series(values.data(), out)) return true;
  model::KelvinSeries k;
  if (!model.kelvin_series(values.data(), &k)) return false;
  *out = k.to_maxwell();  // exact: the relaxation times are the zeros of J*(1/τ)
  return true;
}

model::Moduli<double> moduli_in_mode(const model::Model& model, const std::vector<double>& p,
                                     const model::TestCondition& c, double poisson_ratio) {
  const auto native = model.native_mode();
  if (c.mode == native || !std::isnan(model.bulk_modulus(p.data()))) return model.moduli(p.data(), c);
  model::TestCondition n = c;
  n.mode = native;
  const auto m = model.moduli(p.data(), n);
  const double m0 = instantaneous_MPa(model, p, n, m.storage, c.mode);
  const auto e = elastic_constants(native, m0, std::nan(""), poisson_ratio);
  const auto M = convert({m.storage, m.loss}, native, c.mode, e);
  const auto mean = convert({m.mean, 0.0}, native, c.mode, e);
  return {M.real(), M.imag(), mean.real()};
}

double point_bulk_modulus_MPa(const model::Model& model, const std::vector<double>& p,
                              const model::TestCondition& c, double poisson_ratio) {
  if (!std::isnan(model.bulk_modulus(p.data()))) return std::nan("");
  model::TestCondition n = c;
  n.mode = model.native_mode();
  const double m0 = instantaneous_MPa(model, p, n, model.moduli(p.data(), n).storage, model::TestMode::bulk);
  return elastic_constants(n.mode, m0, std::nan(""), poisson_ratio).bulk_MPa;
}

}  // namespace fitlib::card
