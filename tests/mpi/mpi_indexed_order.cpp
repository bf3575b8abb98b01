// Run under mpiexec (ctest SweepMpi.IndexedTextsInIndexOrderOnEveryRank, 3 ranks): the MPI
// executor of the card draws (fitlib/mpi/sweep_mpi.hpp) gives every rank work(k) at index k, for
// texts of any bytes (empty, ':' and NUL inside) and a count that does not divide by the ranks, and
// an error on one rank is thrown on every rank. Exit 0 on every rank when it holds, 1 otherwise.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "fitlib/mpi/sweep_mpi.hpp"

namespace {

std::string text_of(std::size_t k) {
  std::string t(k % 4, ':');
  t += std::string(1, '\0') + std::to_string(k * k) + (k % 3 == 0 ? "" : "x:y");
  return k == 5 ? std::string() : t;
}

}  // namespace

int main() {
  fitlib::mpi::Session session;
  fitlib::mpi::MpiIndexedExecutor executor(session, 2);
  int failures = 0;
  for (std::size_t n : {0u, 1u, 10u, 31u}) {
    const auto texts = executor.texts(n, 1, [&](std::size_t k) {
      if (k % static_cast<std::size_t>(session.size()) != static_cast<std::size_t>(session.rank()))
        throw std::logic_error("index " + std::to_string(k) + " ran on rank " + std::to_string(session.rank()));
      return text_of(k);
    });
    if (texts.size() != n) ++failures, std::fprintf(stderr, "rank %d: %zu texts of %zu\n", session.rank(), texts.size(), n);
    for (std::size_t k = 0; k < texts.size(); ++k)
      if (texts[k] != text_of(k)) ++failures, std::fprintf(stderr, "rank %d: text %zu differs\n", session.rank(), k);
  }
  bool thrown = false;
  try {
    executor.texts(6, 1, [&](std::size_t k) -> std::string {
      if (k == 4) throw std::runtime_error("draw 4 failed");
      return "ok";
    });
  } catch (const std::runtime_error& e) {
    thrown = std::string(e.what()).find("draw 4 failed") != std::string::npos;
  }
  if (!thrown) ++failures, std::fprintf(stderr, "rank %d: the failure of draw 4 was not thrown here\n", session.rank());
  if (failures == 0 && session.rank() == 0) std::printf("indexed texts in index order on %d ranks\n", session.size());
  return failures == 0 ? 0 : 1;
}
