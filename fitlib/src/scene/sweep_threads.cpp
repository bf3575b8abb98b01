// The rows of a list of cases on a pool of threads (docs/sweep.md "Running").
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "fitlib/scene/sweep_run.hpp"

namespace fitlib::scene {

void run_indexed_in_threads(std::size_t n, int threads, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  // Dynamic schedule: each thread takes the next index.
  auto work = [&] {
    for (std::size_t k = next++; k < n; k = next++) {
      try {
        body(k);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = n;
      }
    }
  };
  const auto count = static_cast<std::size_t>(threads < 1 ? 1 : threads);
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < std::min(count, n); ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

std::vector<std::string> ThreadIndexedExecutor::texts(std::size_t n, int threads,
                                                     const std::function<std::string(std::size_t)>& work) {
  std::vector<std::string> out(n);
  run_indexed_in_threads(n, threads, [&](std::size_t k) { out[k] = work(k); });
  return out;
}

std::vector<std::string> sweep_rows_in_threads(const Sweep& sweep, const std::vector<std::size_t>& cases,
                                               int threads) {
  std::vector<std::string> rows(cases.size());  // rows land at their own index
  run_indexed_in_threads(cases.size(), threads, [&](std::size_t k) { rows[k] = sweep_row(sweep, cases[k]); });
  return rows;
}

std::vector<std::string> ThreadExecutor::rows(const Sweep& sweep, std::size_t begin, std::size_t end) {
  std::vector<std::size_t> cases;
  for (std::size_t i = begin; i < end; ++i) cases.push_back(i);
  return sweep_rows_in_threads(sweep, cases, threads_);
}

}  // namespace fitlib::scene
