#include "worker_pool.hpp"

#include <algorithm>
#include <chrono>

namespace fitlib::segment::detail {

WorkerPool::WorkerPool(int threads) {
  for (int t = 1; t < threads; ++t) helpers_.emplace_back([this] { helper_loop(); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

void WorkerPool::take_chunks(Loop& loop) {
  for (int begin = loop.next.fetch_add(loop.chunk); begin < loop.count; begin = loop.next.fetch_add(loop.chunk)) {
    const int end = std::min(loop.count, begin + loop.chunk);
    try {
      for (int i = begin; i < end; ++i) (*loop.body)(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!loop.error) loop.error = std::current_exception();
    }
    if (loop.done.fetch_add(end - begin) + (end - begin) == loop.count) {
      std::lock_guard<std::mutex> lock(mutex_);  // the caller checks `done` under the lock: no lost wake-up
      finished_.notify_all();
    }
  }
}

void WorkerPool::helper_loop() {
  int seen = 0;
  for (;;) {
    spin_for_next(seen);
    std::shared_ptr<Loop> loop;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      loop = loop_;
    }
    if (loop) take_chunks(*loop);  // a loop that has ended meanwhile has no chunk left
  }
}

// A short spin before sleeping: the next loop usually follows within a factorisation's time, and
// a sleeping helper wakes too late for an assembly of ~0.35 ms (docs/segment.md §Cost). Bounded,
// so an idle team stops burning CPU soon.
void WorkerPool::spin_for_next(int seen) const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicroseconds);
  while (published_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < until)
    std::this_thread::yield();
}

void WorkerPool::for_each(int count, const std::function<void(int)>& body, int chunk) {
  if (helpers_.empty() || count <= chunk) {  // no synchronisation where there is nothing to share
    for (int i = 0; i < count; ++i) body(i);
    return;
  }
  auto loop = std::make_shared<Loop>();
  loop->body = &body, loop->count = count, loop->chunk = chunk;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    loop_ = loop;
    ++generation_;
    published_.store(generation_, std::memory_order_release);
  }
  wake_.notify_all();
  take_chunks(*loop);
  // The helpers' last chunks usually end within microseconds: wait for them spinning, as they wait for
  // the next loop, before sleeping (a sleeping caller wakes tens of microseconds late).
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(kSpinMicroseconds);
  while (loop->done.load(std::memory_order_acquire) < count && std::chrono::steady_clock::now() < until)
    std::this_thread::yield();
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return loop->done.load() == count; });
  if (loop->error) std::rethrow_exception(loop->error);
}

}  // namespace fitlib::segment::detail
