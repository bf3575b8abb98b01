// Sweeps across MPI ranks: rows gathered on rank 0 (MPI_Gatherv of each rank's rows as text).
#include "fitlib/mpi/sweep_mpi.hpp"

#include <mpi.h>

#include <cstdlib>
#include <stdexcept>

namespace fitlib::mpi {

bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

Session::Session() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Session::~Session() { MPI_Finalize(); }

MpiExecutor::MpiExecutor(const Session& session, int threads)
    : rank_(session.rank()), size_(session.size()), threads_(threads < 1 ? 1 : threads) {}

std::size_t MpiExecutor::share(std::size_t writer_value) {
  unsigned long long v = writer_value;
  MPI_Bcast(&v, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  return static_cast<std::size_t>(v);
}

namespace {

// This rank's rows as one text: a status byte ('+' rows follow, '!' an error message follows),
// then the rows, each ended by '\n'.
std::string local_rows(const scene::Sweep& sweep, std::size_t begin, std::size_t end, int rank, int size,
                       int threads) {
  std::vector<std::size_t> cases;
  for (std::size_t i = begin; i < end; ++i)
    if (i % static_cast<std::size_t>(size) == static_cast<std::size_t>(rank)) cases.push_back(i);
  try {
    std::string text = "+";
    for (const auto& row : scene::sweep_rows_in_threads(sweep, cases, threads)) text += row + "\n";
    return text;
  } catch (const std::exception& e) {
    return std::string("!rank ") + std::to_string(rank) + ": " + e.what();
  }
}

}  // namespace

std::vector<std::string> MpiExecutor::rows(const scene::Sweep& sweep, std::size_t begin, std::size_t end) {
  const std::string mine = local_rows(sweep, begin, end, rank_, size_, threads_);
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(size_), offsets(size_);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank_ == 0) {
    for (int r = 1; r < size_; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    all.resize(static_cast<std::size_t>(offsets[size_ - 1] + lengths[size_ - 1]));
  }
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
              MPI_COMM_WORLD);
  std::string failure;
  if (rank_ == 0)
    for (int r = 0; r < size_ && failure.empty(); ++r)
      if (all[offsets[r]] == '!') failure = all.substr(offsets[r] + 1, lengths[r] - 1);
  if (share(failure.empty() ? 0 : 1)) throw std::runtime_error(rank_ == 0 ? failure : "another rank failed");
  if (rank_ != 0) return {};
  // Case i's row is the next unread row of rank i mod N.
  std::vector<std::size_t> cursor(size_);
  for (int r = 0; r < size_; ++r) cursor[r] = static_cast<std::size_t>(offsets[r]) + 1;
  std::vector<std::string> rows;
  for (std::size_t i = begin; i < end; ++i) {
    const int r = static_cast<int>(i % static_cast<std::size_t>(size_));
    const std::size_t nl = all.find('\n', cursor[r]);
    rows.push_back(all.substr(cursor[r], nl - cursor[r]));
    cursor[r] = nl + 1;
  }
  return rows;
}

}  // namespace fitlib::mpi
