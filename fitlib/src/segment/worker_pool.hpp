#pragma once
// A fixed team of threads for the segment solver's element loop (docs/decisions.md "Segment: the
// element loop on a team of std::threads"). The caller is the team's first member; the helpers
// spin (yielding) for at most 1 ms, then sleep on a condition variable between loops, and take
// chunks of the index range from the loop's atomic counter; the caller waits for the indices, not
// for the helpers, so a helper that wakes late (a loaded machine) delays nobody. The loop's body
// must write only to its own index's outputs; the order the indices run in is free.
#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace fitlib::segment::detail {

class WorkerPool {
 public:
  explicit WorkerPool(int threads);  // threads ≥ 1 (1: no helper, the loop runs on the caller)
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(helpers_.size()) + 1; }
  // body(i) for every i in [0, count), across the team, `chunk` indices per take (the elements: a
  // few, as they cost alike; 1 for a few large tasks); returns when all have run. The first
  // exception a body throws is rethrown here, after the loop.
  static constexpr int kElementChunk = 4;
  void for_each(int count, const std::function<void(int)>& body, int chunk = kElementChunk);

 private:
  struct Loop {  // one for_each; shared, so a helper waking after it has ended finds it done
    const std::function<void(int)>* body = nullptr;
    int count = 0, chunk = kElementChunk;
    std::atomic<int> next{0}, done{0};
    std::exception_ptr error;
  };
  void helper_loop();
  void spin_for_next(int seen) const;
  void take_chunks(Loop& loop);  // runs chunks of the loop until none is left

  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::shared_ptr<Loop> loop_;
  int generation_ = 0;
  std::atomic<int> published_{0};  // generation_, readable without the lock (the helpers' spin)
  static constexpr int kSpinMicroseconds = 1000;
  bool stop_ = false;
};

}  // namespace fitlib::segment::detail
