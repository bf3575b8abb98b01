#include "term_merge.hpp"

#include <cstddef>
#include <limits>

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

}  // namespace fitlib::fit::detail
