#include "grouped_ldlt.hpp"

#include <algorithm>

#include <amd.h>
#include <camd.h>

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

std::vector<int> grouped_amd_order(const SparseMatrix& K, const std::vector<int>& last) {
  const int n = static_cast<int>(K.cols());
  std::vector<int> group(n), first;  // group of each equation, first equation of each group
  for (int j = 0; j < n; ++j) {
    if (j == 0 || !same_column_pattern(K, j, j - 1) || (!last.empty() && last[j] != last[j - 1])) first.push_back(j);
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
  bool ordered = false;
  if (last.empty()) {
    double control[AMD_CONTROL], info[AMD_INFO];
    amd_defaults(control);
    ordered = amd_order(groups, quotient_outer.data(), quotient_inner.data(), group_order.data(), control, info) == AMD_OK;
  } else {  // CAMD: the groups marked `last` after the others, each set ordered knowing the other
    std::vector<int> constraint(groups);
    for (int g = 0; g < groups; ++g) constraint[g] = last[first[g]] ? 1 : 0;
    double control[CAMD_CONTROL], info[CAMD_INFO];
    camd_defaults(control);
    ordered = camd_order(groups, quotient_outer.data(), quotient_inner.data(), group_order.data(), control, info,
                         constraint.data()) == CAMD_OK;
  }
  if (!ordered) throw core::NumericalError("segment: AMD ordering of the tangent's pattern failed");
  std::vector<int> order;
  for (int p = 0; p < groups; ++p) {
    const int g = group_order[p];
    const int end = g + 1 < groups ? first[g + 1] : n;
    for (int j = first[g]; j < end; ++j) order.push_back(j);
  }
  return order;
}

}  // namespace fitlib::segment::detail
