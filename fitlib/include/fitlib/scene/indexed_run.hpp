#pragma once
// Indexed work on the sweep engine's schedule (docs/sweep.md "Running"): work(k) for k in [0, n),
// each result stored at its own index, so the results do not depend on the number of threads or
// MPI ranks that computed them. The sweep's rows and the life's card draws ([life] uncertainty =
// "cards", docs/thermal.md §7) both run on it.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace fitlib::scene {

// Runs work(k) for every k in [0, n) on `threads` threads, each taking the next index as it frees
// up (the sweep's schedule); the first exception stops the rest and is rethrown. A result stored
// at its own index is the same for any number of threads.
void run_indexed_in_threads(std::size_t n, int threads, const std::function<void(std::size_t)>& work);

// Texts of indexed work, on one process's threads or across processes (MPI ranks:
// fitlib/mpi/sweep_mpi.hpp's MpiIndexedExecutor). Every process that calls texts() gets all n
// texts in index order; a text is any bytes.
class IndexedExecutor {
 public:
  virtual ~IndexedExecutor() = default;
  // texts[k] = work(k); `threads` is the caller's thread count on one process (an executor across
  // processes uses its own per process).
  virtual std::vector<std::string> texts(std::size_t n, int threads,
                                         const std::function<std::string(std::size_t)>& work) = 0;
};

// The one-process executor: run_indexed_in_threads.
class ThreadIndexedExecutor : public IndexedExecutor {
 public:
  std::vector<std::string> texts(std::size_t n, int threads,
                                 const std::function<std::string(std::size_t)>& work) override;
};

}  // namespace fitlib::scene
