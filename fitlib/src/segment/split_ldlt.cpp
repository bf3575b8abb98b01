#include "split_ldlt.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "grouped_ldlt.hpp"

namespace fitlib::segment::detail {
namespace {

using SparseMatrix = SplitLdlt::SparseMatrix;

// Breadth-first levels of K's graph from `start` (-1: not reached).
std::vector<int> levels_from(const SparseMatrix& K, int start) {
  std::vector<int> level(K.cols(), -1);
  std::deque<int> queue{start};
  level[start] = 0;
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    for (SparseMatrix::InnerIterator it(K, v); it; ++it)
      if (level[it.index()] < 0) level[it.index()] = level[v] + 1, queue.push_back(it.index());
  }
  return level;
}

// Levels from a pseudo-peripheral equation (the farthest from the farthest of equation 0), so the
// level sets cut the long strip across.
std::vector<int> peripheral_levels(const SparseMatrix& K) {
  std::vector<int> level = levels_from(K, 0);
  for (int pass = 0; pass < 2; ++pass)
    level = levels_from(K, static_cast<int>(std::max_element(level.begin(), level.end()) - level.begin()));
  return level;
}

// The level set that leaves at least `smallest` equations on either side with the least larger side
// plus twice its own size (the halves run at once, so the larger one sets the time; the separator's
// rows fill densely in both); -1: none.
int separator_level(const std::vector<int>& level, int smallest) {
  const int depth = *std::max_element(level.begin(), level.end()) + 1;
  std::vector<int> count(depth, 0);
  for (int l : level) ++count[l];
  int best = -1, best_cost = 0, before = 0;
  const int n = static_cast<int>(level.size());
  for (int d = 0; d < depth; before += count[d], ++d) {
    const int after = n - before - count[d], cost = std::max(before, after) + 2 * count[d];
    if (before >= smallest && after >= smallest && (best < 0 || cost < best_cost)) best = d, best_cost = cost;
  }
  return best;
}

// K's pattern restricted to `equations` (local numbering by position; −1 in `local` elsewhere).
SparseMatrix sub_pattern(const SparseMatrix& K, const std::vector<int>& equations, const std::vector<int>& local) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t c = 0; c < equations.size(); ++c)
    for (SparseMatrix::InnerIterator it(K, equations[c]); it; ++it)
      if (local[it.index()] >= 0) entries.emplace_back(local[it.index()], static_cast<int>(c), 1.0);
  SparseMatrix P(equations.size(), equations.size());
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

}  // namespace

bool SplitLdlt::analyze(const SparseMatrix& K) {
  const int n = static_cast<int>(K.cols());
  if (n < 64) return false;
  const std::vector<int> level = peripheral_levels(K);
  if (std::count(level.begin(), level.end(), -1) > 0) return false;  // not connected
  const int d = separator_level(level, static_cast<int>(kSmallestHalf * n));
  if (d < 0) return false;
  separator_.clear();
  std::array<std::vector<int>, 2> interior;
  for (int j = 0; j < n; ++j) (level[j] < d ? interior[0] : level[j] > d ? interior[1] : separator_).push_back(j);
  const int nS = static_cast<int>(separator_.size());
  std::vector<int> in_S(n, -1);
  for (int i = 0; i < nS; ++i) in_S[separator_[i]] = i;
  k_SS_.clear();
  for (int j = 0; j < nS; ++j)
    for (SparseMatrix::InnerIterator it(K, separator_[j]); it; ++it)
      if (in_S[it.index()] >= 0) k_SS_.push_back({in_S[it.index()], j, static_cast<int>(&it.value() - K.valuePtr())});
  for (int h = 0; h < 2; ++h) {
    Half& half = halves_[h];
    half.interior = static_cast<int>(interior[h].size());
    // The interior in the node groups' CAMD order of the block with S last (fill-reducing knowing
    // S), then S in the separator's order (the same in both halves).
    std::vector<int> block = interior[h], local(n, -1), last(half.interior, 0);
    block.insert(block.end(), separator_.begin(), separator_.end());
    last.resize(block.size(), 1);
    for (std::size_t i = 0; i < block.size(); ++i) local[block[i]] = static_cast<int>(i);
    const std::vector<int> order = grouped_amd_order(sub_pattern(K, block, local), last);
    half.global.clear();
    for (int i : order)
      if (i < half.interior) half.global.push_back(block[i]);
    half.global.insert(half.global.end(), separator_.begin(), separator_.end());
    std::fill(local.begin(), local.end(), -1);
    for (std::size_t i = 0; i < half.global.size(); ++i) local[half.global[i]] = static_cast<int>(i);
    // The block's upper triangle, each entry's value its slot in K (exact in a double) until read.
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t c = 0; c < half.global.size(); ++c)
      for (SparseMatrix::InnerIterator it(K, half.global[c]); it; ++it)
        if (local[it.index()] >= 0 && local[it.index()] <= static_cast<int>(c))
          entries.emplace_back(local[it.index()], static_cast<int>(c), double(&it.value() - K.valuePtr()));
    half.M.resize(half.global.size(), half.global.size());
    half.M.setFromTriplets(entries.begin(), entries.end());
    half.source.assign(half.M.valuePtr(), half.M.valuePtr() + half.M.nonZeros());
    half.ldlt.analyzePattern(half.M);
    half.work.resize(half.global.size());
  }
  return true;
}

void SplitLdlt::factorize_half(const SparseMatrix& K, Half& h) const {
  for (std::size_t k = 0; k < h.source.size(); ++k) h.M.valuePtr()[k] = K.valuePtr()[h.source[k]];
  h.ldlt.factorize(h.M);
  h.ok = h.ldlt.info() == Eigen::Success;
  if (!h.ok) return;
  // T_h = L_SS D_S L_SSᵀ from the trailing columns of the half's factor (unit lower, strictly lower stored).
  const int nS = static_cast<int>(separator_.size());
  const SparseMatrix& L = h.ldlt.matrixL().nestedExpression();
  Eigen::MatrixXd L_SS = Eigen::MatrixXd::Identity(nS, nS);
  for (int j = 0; j < nS; ++j)
    for (SparseMatrix::InnerIterator it(L, h.interior + j); it; ++it) L_SS(it.index() - h.interior, j) = it.value();
  h.trailing.noalias() = L_SS * h.ldlt.vectorD().tail(nS).asDiagonal() * L_SS.transpose();
}

bool SplitLdlt::factorize(const SparseMatrix& K, WorkerPool& pool) {
  pool.for_each(2, [&](int h) { factorize_half(K, halves_[h]); }, 1);
  if (!halves_[0].ok || !halves_[1].ok) return false;
  Eigen::MatrixXd schur = halves_[0].trailing + halves_[1].trailing;
  for (const auto& e : k_SS_) schur(e[0], e[1]) -= K.valuePtr()[e[2]];
  schur_.compute(schur);
  return std::isfinite(schur_.rcond()) && schur_.rcond() > 0.0;
}

void SplitLdlt::forward(const Half& h, const Eigen::VectorXd& b) const {
  Eigen::VectorXd& w = h.work;
  for (int k = 0; k < h.interior; ++k) w[k] = b[h.global[k]];
  w.tail(separator_.size()).setZero();
  const SparseMatrix& L = h.ldlt.matrixL().nestedExpression();
  const int* outer = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  const double* value = L.valuePtr();
  for (int j = 0; j < h.interior; ++j) {
    const double x = w[j];
    if (x != 0.0)
      for (int p = outer[j]; p < outer[j + 1]; ++p) w[row[p]] -= value[p] * x;
  }
}

void SplitLdlt::backward(const Half& h, const Eigen::VectorXd& x_S, Eigen::VectorXd& x) const {
  Eigen::VectorXd& w = h.work;
  w.head(h.interior).array() /= h.ldlt.vectorD().head(h.interior).array();
  w.tail(separator_.size()) = x_S;
  const SparseMatrix& L = h.ldlt.matrixL().nestedExpression();
  const int* outer = L.outerIndexPtr();
  const int* row = L.innerIndexPtr();
  const double* value = L.valuePtr();
  for (int j = h.interior - 1; j >= 0; --j) {
    double s = w[j];
    for (int p = outer[j]; p < outer[j + 1]; ++p) s -= value[p] * w[row[p]];
    w[j] = s;
  }
  for (int k = 0; k < h.interior; ++k) x[h.global[k]] = w[k];
}

Eigen::VectorXd SplitLdlt::solve(const Eigen::VectorXd& b, WorkerPool& pool) const {
  pool.for_each(2, [&](int h) { forward(halves_[h], b); }, 1);
  const int nS = static_cast<int>(separator_.size());
  Eigen::VectorXd z(nS);
  for (int i = 0; i < nS; ++i) z[i] = b[separator_[i]] + halves_[0].work[halves_[0].interior + i] + halves_[1].work[halves_[1].interior + i];
  const Eigen::VectorXd x_S = schur_.solve(z);
  Eigen::VectorXd x(b.size());
  for (int i = 0; i < nS; ++i) x[separator_[i]] = x_S[i];
  pool.for_each(2, [&](int h) { backward(halves_[h], x_S, x); }, 1);
  return x;
}

}  // namespace fitlib::segment::detail
