#pragma once
// One rule, for eval and the FE exports, for a card's response in a mode it does not describe
// natively when it holds no bulk modulus (docs/decisions.md, "exports: what each FE format
// receives" and "eval: native mode, conversion"): a shear card gets an elastic bulk modulus
// K = 2G₀(1 + ν)/(3(1 − 2ν)) from its instantaneous shear modulus; a uniaxial card keeps the
// Poisson ratio ν constant (bulk relaxes with the same weights).
#include <vector>

#include "fitlib/model/model.hpp"

namespace fitlib::card {

// The Poisson ratio of a card's instantaneous response where it has no bulk modulus: K ≈ 10³ G
// (docs/decisions.md, "exports: what each FE format receives"); eval, export and scenes share it.
inline constexpr double kDefaultPoissonRatio = 0.4995;

// Instantaneous elastic constants of a linear card.
struct ElasticConstants {
  double young0_MPa = 0.0, shear0_MPa = 0.0, bulk_MPa = 0.0, poisson = 0.0;
  bool bulk_relaxes = false;  // uniaxial card without K: constant Poisson ratio
};

// `instantaneous_MPa`: the native-mode instantaneous modulus; `bulk_MPa`: the card's K or NaN;
// `poisson_ratio` applies only when the card has no K.
ElasticConstants elastic_constants(model::TestMode native, double instantaneous_MPa, double bulk_MPa,
                                   double poisson_ratio);

// The model's relaxation series in its native mode, exactly: its own Maxwell series, or a
// retardation spectrum's (KelvinSeries::to_maxwell). False for a model that has neither.
bool exact_maxwell_series(const model::Model& model, const std::vector<double>& values, model::MaxwellSeries* out);

// The card's moduli at `c` in any mode: the model's own when c.mode is its native mode or it has
// a bulk modulus; otherwise converted by elastic_constants from the card's instantaneous modulus
// (a series' glassy one, a shear card's relaxation modulus at t = 0; UsageError for a bulk card).
model::Moduli<double> moduli_in_mode(const model::Model& model, const std::vector<double>& values,
                                     const model::TestCondition& c, double poisson_ratio);

// The bulk modulus K (MPa) a material point of the card needs by the same rule: NaN when the card
// holds its own K (the point takes it), else elastic_constants' K from the instantaneous modulus
// (as moduli_in_mode; a uniaxial card that is no series: the storage at `c`).
double point_bulk_modulus_MPa(const model::Model& model, const std::vector<double>& values,
                              const model::TestCondition& c, double poisson_ratio);

}  // namespace fitlib::card
