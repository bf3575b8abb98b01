#include "grouped_ldlt.hpp"

#include <algorithm>
#include <cmath>

#include <amd.h>

#include "fitlib/core/error.hpp"

namespace fitlib::segment::detail {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

bool same_column_pattern(const SparseMatrix& K, int a, int b) {
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  return outer[a + 1] - outer[a] == outer[b + 1] - outer[b] &&
         std::equal(inner + outer[a], inner + outer[a + 1], inner + outer[b]);
}

}  // namespace

std::vector<int> grouped_amd_order(const SparseMatrix& K) {
  const int n = static_cast<int>(K.cols());
  std::vector<int> group(n), first;  // group of each equation, first equation of each group
  for (int j = 0; j < n; ++j) {
    if (j == 0 || !same_column_pattern(K, j, j - 1)) first.push_back(j);
    group[j] = static_cast<int>(first.size()) - 1;
  }
  const int groups = static_cast<int>(first.size());
  std::vector<int> quotient_outer{0}, quotient_inner, group_order(groups);  // the groups' graph
  for (int g = 0; g < groups; ++g) {
    for (SparseMatrix::InnerIterator it(K, first[g]); it; ++it)
      if (quotient_inner.size() == static_cast<std::size_t>(quotient_outer.back()) || quotient_inner.back() != group[it.index()])
        quotient_inner.push_back(group[it.index()]);  // rows ascend, so a group's rows are consecutive
    quotient_outer.push_back(static_cast<int>(quotient_inner.size()));
  }
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  if (amd_order(groups, quotient_outer.data(), quotient_inner.data(), group_order.data(), control, info) != AMD_OK)
    throw core::NumericalError("segment: AMD ordering of the tangent's pattern failed");
  std::vector<int> order;
  for (int p = 0; p < groups; ++p) {
    const int g = group_order[p];
    const int end = g + 1 < groups ? first[g + 1] : n;
    for (int j = first[g]; j < end; ++j) order.push_back(j);
  }
  return order;
}

void GroupedLdlt::analyze(const SparseMatrix& K) {
  order_ = grouped_amd_order(K);
  const int n = static_cast<int>(K.cols());
  std::vector<int> position(n);
  for (int p = 0; p < n; ++p) position[order_[p]] = p;
  // Each kept entry carries its index in K's value array through setFromTriplets (no duplicates).
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j)
    for (int k = K.outerIndexPtr()[j]; k < K.outerIndexPtr()[j + 1]; ++k) {
      const int r = position[K.innerIndexPtr()[k]], c = position[j];
      if (r <= c) t.emplace_back(r, c, static_cast<double>(k));
    }
  upper_.resize(n, n);
  upper_.setFromTriplets(t.begin(), t.end());
  upper_.makeCompressed();
  from_.assign(upper_.valuePtr(), upper_.valuePtr() + upper_.nonZeros());
  symbolic();
}

// LDL's ldl_symbolic: the elimination tree and the count of each column of L, by walking from each
// entry of column k of the upper triangle up the tree to k.
void GroupedLdlt::symbolic() {
  const int n = static_cast<int>(upper_.cols());
  const int* outer = upper_.outerIndexPtr();
  const int* inner = upper_.innerIndexPtr();
  parent_.assign(n, -1), flag_.assign(n, -1), filled_.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    flag_[k] = k;
    for (int p = outer[k]; p < outer[k + 1]; ++p)
      for (int i = inner[p]; i < k && flag_[i] != k; i = parent_[i]) {
        if (parent_[i] == -1) parent_[i] = k;
        ++filled_[i], flag_[i] = k;
      }
  }
  L_start_.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) L_start_[j + 1] = L_start_[j] + filled_[j];
  pair_first_.assign(n, 0);
  for (int j = 0; j + 1 < n; ++j)
    pair_first_[j] = parent_[j] == j + 1 && filled_[j] == filled_[j + 1] + 1 && !(j > 0 && pair_first_[j - 1]);
  L_rows_.resize(L_start_[n]), L_values_.resize(L_start_[n]);
  D_.resize(n), y_.assign(n, 0.0), pair_y_.assign(n, 0.0), pattern_.resize(n);
}

// LDL's ldl_numeric, row k of L at a time. Where columns j, j + 1 form a pair, j's update of the
// rows they share waits (its y kept in pair_y_[j]) for j + 1's, and both go in one pass: those rows
// are ancestors of j + 1 in the tree, so none is read before j + 1 is eliminated.
bool GroupedLdlt::numeric() {
  const int n = static_cast<int>(upper_.cols());
  const int* outer = upper_.outerIndexPtr();
  const int* inner = upper_.innerIndexPtr();
  const double* a = upper_.valuePtr();
  int* rows = L_rows_.data();
  double* values = L_values_.data();
  double* y = y_.data();
  for (int k = 0; k < n; ++k) {
    int top = n;  // pattern of row k of L, topological order, in pattern_[top, n)
    flag_[k] = k, filled_[k] = 0, y[k] = 0.0;
    for (int p = outer[k]; p < outer[k + 1]; ++p) {
      int i = inner[p], len = 0;
      y[i] += a[p];
      for (; flag_[i] != k; i = parent_[i]) pattern_[len++] = i, flag_[i] = k;
      while (len > 0) pattern_[--top] = pattern_[--len];
    }
    double d = y[k];
    y[k] = 0.0;
    for (; top < n; ++top) {
      const int i = pattern_[top];
      const double yi = y[i];
      y[i] = 0.0;
      const int begin = L_start_[i], end = begin + filled_[i];
      if (pair_first_[i]) {
        if (end > begin) y[i + 1] -= values[begin] * yi;  // row i + 1 is column i's first
        pair_y_[i] = yi;
      } else if (i > 0 && pair_first_[i - 1] && flag_[i - 1] == k) {
        const int shift = L_start_[i - 1] + 1 - begin;  // column i − 1 past its row i, aligned with i
        const double y_first = pair_y_[i - 1];
        for (int p = begin; p < end; ++p) y[rows[p]] -= values[p] * yi + values[p + shift] * y_first;
      } else {
        for (int p = begin; p < end; ++p) y[rows[p]] -= values[p] * yi;
      }
      const double l_ki = yi / D_[i];
      d -= l_ki * yi;
      rows[end] = k, values[end] = l_ki, ++filled_[i];
    }
    if (d == 0.0 || !std::isfinite(d)) return false;
    D_[k] = d;
  }
  return true;
}

bool GroupedLdlt::factorize(const SparseMatrix& K) {
  double* values = upper_.valuePtr();
  const double* source = K.valuePtr();
  for (std::size_t k = 0; k < from_.size(); ++k) values[k] = source[from_[k]];
  return numeric();
}

Eigen::VectorXd GroupedLdlt::solve(const Eigen::VectorXd& b) const {
  const int n = static_cast<int>(order_.size());
  Eigen::VectorXd y(n), x(n);
  for (int p = 0; p < n; ++p) y[p] = b[order_[p]];
  for (int j = 0; j < n; ++j)  // L y = P b
    for (int p = L_start_[j]; p < L_start_[j + 1]; ++p) y[L_rows_[p]] -= L_values_[p] * y[j];
  for (int j = 0; j < n; ++j) y[j] /= D_[j];
  for (int j = n - 1; j >= 0; --j)  // Lᵀ
    for (int p = L_start_[j]; p < L_start_[j + 1]; ++p) y[j] -= L_values_[p] * y[L_rows_[p]];
  for (int p = 0; p < n; ++p) x[order_[p]] = y[p];
  return x;
}

int GroupedLdlt::pairs() const { return static_cast<int>(std::count(pair_first_.begin(), pair_first_.end(), 1)); }

}  // namespace fitlib::segment::detail
