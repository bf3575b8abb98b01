#include "term_merge.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "admissible.hpp"
#include "spectrum_system.hpp"

namespace fitlib::fit::detail {

std::vector<Term> merge_to(std::vector<Term> terms, int n) {
  while (static_cast<int>(terms.size()) > n) {
    std::size_t best = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k + 1 < terms.size(); ++k) {
      const Term& a = terms[k];
      const Term& b = terms[k + 1];
      const double sum = a.modulus + b.modulus;
      const double d = b.log_tau - a.log_tau;
      const double cost = sum > 0.0 ? a.modulus * b.modulus / sum * d * d : 0.0;
      if (cost < best_cost) best_cost = cost, best = k;
    }
    Term& a = terms[best];
    const Term& b = terms[best + 1];
    const double sum = a.modulus + b.modulus;
    a.log_tau = sum > 0.0 ? (a.modulus * a.log_tau + b.modulus * b.log_tau) / sum : 0.5 * (a.log_tau + b.log_tau);
    a.modulus = sum;
    terms.erase(terms.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  }
  return terms;
}

std::vector<Term> positive_terms(const FitResult& spectrum) {
  const SeriesTerms s = series_terms(spectrum.model->parameters());
  std::vector<Term> terms;
  for (std::size_t k = 0; k < s.times.size(); ++k)
    if (spectrum.values[s.moduli[k]] > 0.0)
      terms.push_back({spectrum.values[s.moduli[k]], std::log(spectrum.values[s.times[k]])});
  std::sort(terms.begin(), terms.end(), [](const Term& a, const Term& b) { return a.log_tau < b.log_tau; });
  return terms;
}

std::vector<double> start_from_terms(const model::Model& m, const FitResult& spectrum, const std::vector<Term>& terms) {
  const SeriesTerms ms = series_terms(m.parameters());
  std::vector<double> start(m.size(), 0.0);
  for (std::size_t k = 0; k < terms.size() && k < ms.moduli.size(); ++k) {
    start[ms.moduli[k]] = terms[k].modulus;
    start[ms.times[k]] = std::exp(terms[k].log_tau);
  }
  set_non_series_values(m, non_series_values(*spectrum.model, spectrum.values), start);
  return start;
}

}  // namespace fitlib::fit::detail
