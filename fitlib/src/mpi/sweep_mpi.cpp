// Indexed work across MPI ranks (docs/sweep.md "MPI"): index i runs on rank i mod N with that
// rank's threads; each rank's texts are gathered (MPI_Gatherv to rank 0 for the sweep's rows,
// MPI_Allgatherv to every rank for the life's card draws) and put back in index order.
#include "fitlib/mpi/sweep_mpi.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <thread>

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

namespace {

// Waits for `request` without spinning: a rank that finished its share early (under the life's card
// draws every rank but 0, which also runs the deterministic life) sleeps in 1 ms steps instead of
// polling at full speed in a blocking collective, so the time it waits costs no CPU
// (docs/decisions.md "Card draws under MPI: rank 0 alone runs the deterministic life").
void wait_idle(MPI_Request& request) {
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

std::size_t broadcast(std::size_t writer_value) {
  unsigned long long v = writer_value;
  MPI_Bcast(&v, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  return static_cast<std::size_t>(v);
}

// This rank's texts of [begin, end) as one text: a status byte ('+' texts follow, '!' an error
// message follows), then each text as "<length>:<bytes>" (a text may hold any byte).
std::string local_texts(std::size_t begin, std::size_t end, int rank, int size, int threads,
                        const std::function<std::string(std::size_t)>& work) {
  std::vector<std::size_t> mine;
  for (std::size_t i = begin; i < end; ++i)
    if (i % static_cast<std::size_t>(size) == static_cast<std::size_t>(rank)) mine.push_back(i);
  try {
    std::vector<std::string> texts(mine.size());
    scene::run_indexed_in_threads(mine.size(), threads, [&](std::size_t k) { texts[k] = work(mine[k]); });
    std::string packed = "+";
    for (const std::string& t : texts) packed += std::to_string(t.size()) + ":" + t;
    return packed;
  } catch (const std::exception& e) {
    return std::string("!rank ") + std::to_string(rank) + ": " + e.what();
  }
}

// work(i) for i in [begin, end) in index order, on rank 0 (to_all false; the others get nothing)
// or on every rank. An error on any rank is thrown on every rank (with its message where the
// texts land).
std::vector<std::string> gather_texts(int rank, int size, int threads, std::size_t begin, std::size_t end,
                                      const std::function<std::string(std::size_t)>& work, bool to_all) {
  const std::string mine = local_texts(begin, end, rank, size, threads, work);
  int length = static_cast<int>(mine.size());
  std::vector<int> lengths(size), offsets(size);
  const bool receives = to_all || rank == 0;
  MPI_Request request;  // the lengths arrive when the slowest rank is done: waited for idle
  if (to_all) MPI_Iallgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  else MPI_Igather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait_idle(request);
  std::string all;
  if (receives) {
    for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    all.resize(static_cast<std::size_t>(offsets[size - 1] + lengths[size - 1]));
  }
  if (to_all)
    MPI_Allgatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
                   MPI_COMM_WORLD);
  else
    MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                MPI_COMM_WORLD);
  std::string failure;
  if (receives)
    for (int r = 0; r < size && failure.empty(); ++r)
      if (all[offsets[r]] == '!') failure = all.substr(offsets[r] + 1, lengths[r] - 1);
  if (to_all ? !failure.empty() : broadcast(failure.empty() ? 0 : 1) != 0)
    throw std::runtime_error(receives ? failure : "another rank failed");
  if (!receives) return {};
  // Index i's text is the next unread text of rank i mod N.
  std::vector<std::size_t> cursor(size);
  for (int r = 0; r < size; ++r) cursor[r] = static_cast<std::size_t>(offsets[r]) + 1;
  std::vector<std::string> texts;
  for (std::size_t i = begin; i < end; ++i) {
    std::size_t& at = cursor[i % static_cast<std::size_t>(size)];
    const std::size_t colon = all.find(':', at);
    const std::size_t n = std::stoull(all.substr(at, colon - at));
    texts.push_back(all.substr(colon + 1, n));
    at = colon + 1 + n;
  }
  return texts;
}

}  // namespace

MpiExecutor::MpiExecutor(const Session& session, int threads)
    : rank_(session.rank()), size_(session.size()), threads_(threads < 1 ? 1 : threads) {}

std::size_t MpiExecutor::share(std::size_t writer_value) { return broadcast(writer_value); }

std::vector<std::string> MpiExecutor::rows(const scene::Sweep& sweep, std::size_t begin, std::size_t end) {
  return gather_texts(rank_, size_, threads_, begin, end, [&](std::size_t i) { return scene::sweep_row(sweep, i); },
                      false);
}

MpiIndexedExecutor::MpiIndexedExecutor(const Session& session, int threads)
    : rank_(session.rank()), size_(session.size()), threads_(threads < 1 ? 1 : threads) {}

std::vector<std::string> MpiIndexedExecutor::texts(std::size_t n, int /*threads: the rank's own*/,
                                                   const std::function<std::string(std::size_t)>& work) {
  return gather_texts(rank_, size_, threads_, 0, n, work, true);
}

}  // namespace fitlib::mpi
