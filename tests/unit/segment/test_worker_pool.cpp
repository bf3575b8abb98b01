// The element loop's team of threads (fitlib/src/segment/worker_pool.hpp): every index runs exactly
// once whatever the team size and the loop length, loops follow each other on the same team, and an
// exception of a body reaches the caller after the loop (the team stays usable).
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "../../../fitlib/src/segment/worker_pool.hpp"

using fitlib::segment::detail::WorkerPool;

TEST(SegmentWorkerPool, RunsEveryIndexExactlyOnceOverManyLoops) {
  for (int threads : {1, 2, 3}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (int count : {0, 1, 3, 4, 5, 17, 192, 1000}) {
      for (int repeat = 0; repeat < 20; ++repeat) {
        std::vector<std::atomic<int>> hits(count);
        pool.for_each(count, [&](int i) { hits[i].fetch_add(1); });
        for (int i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << threads << " threads, " << count << " indices";
      }
    }
  }
}

TEST(SegmentWorkerPool, SharesTheWorkAndRethrowsABodysException) {
  WorkerPool pool(2);
  std::vector<int> squares(500, 0);
  pool.for_each(500, [&](int i) { squares[i] = i * i; });
  for (int i = 0; i < 500; ++i) ASSERT_EQ(squares[i], i * i);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.for_each(300, [&](int i) {
    ran.fetch_add(1);
    if (i == 123) throw std::runtime_error("element 123");
  }), std::runtime_error);
  EXPECT_GE(ran.load(), 124);  // the loop ran on: its chunks are independent
  pool.for_each(500, [&](int i) { squares[i] = -i; });  // still usable
  for (int i = 0; i < 500; ++i) ASSERT_EQ(squares[i], -i);
}
