// The parallel loops and the pool they run on: every index once, whatever the threads, from
// nested loops and from several calling threads at once, and an exception thrown by an
// iteration reaches the caller (it must not terminate the program from inside a worker).

#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/thread_pool.h"
#include "core/parallel.h"

namespace radrecon {
namespace parallel_test {

TEST(ParallelFor, VisitsEveryIndexOnceOnOneAndTwoThreads) {
  const int threads = worker_thread_count();
  for (int t : {1, 2, 5}) {
    set_worker_thread_count(t);
    for (std::int64_t n : {0, 1, 511, 512, 513, 100'000}) {
      std::vector<int> seen(static_cast<size_t>(n), 0);
      parallel_for(0, n, [&](std::int64_t i) { ++seen[static_cast<size_t>(i)]; });
      for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(seen[static_cast<size_t>(i)], 1) << "n " << n << ", i " << i;
      std::vector<int> with_scratch(static_cast<size_t>(n), 0);
      parallel_for_with_scratch<std::vector<int>>(0, n, [&](std::int64_t i, std::vector<int>& scratch) {
        scratch.assign(1, static_cast<int>(i));
        with_scratch[static_cast<size_t>(i)] += scratch[0] == i;
      });
      for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(with_scratch[static_cast<size_t>(i)], 1);
    }
  }
  set_worker_thread_count(threads);
}

TEST(ParallelFor, AnExceptionFromAnIterationIsRethrownToTheCaller) {
  const int threads = worker_thread_count();
  set_worker_thread_count(2);
  EXPECT_THROW(parallel_for(0, 100'000,
                            [](std::int64_t i) {
                              if (i == 77'777) throw std::bad_alloc();
                            }),
               std::bad_alloc);
  EXPECT_THROW(parallel_for_with_scratch<int>(0, 100'000,
                                              [](std::int64_t i, int&) {
                                                if (i == 5) throw std::runtime_error("iteration 5");
                                              }),
               std::runtime_error);
  set_worker_thread_count(threads);
}

TEST(ParallelFor, NestedLoopsAndSeveralCallersEachVisitEveryIndexOnce) {
  const int threads = worker_thread_count();
  set_worker_thread_count(3);
  // A loop inside a loop's iteration runs on that iteration's thread.
  std::vector<std::atomic<int>> seen(64 * 1000);
  parallel_for_coarse(0, 64, [&](std::int64_t outer) {
    parallel_for(0, 1000, [&](std::int64_t inner) { ++seen[static_cast<size_t>(outer * 1000 + inner)]; });
  });
  for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i].load(), 1) << i;
  // Four threads calling loops at once (the Python module's callers): one holds the pool, the
  // others run theirs alone, and every loop is whole.
  std::vector<std::vector<int>> counts(4, std::vector<int>(50'000, 0));
  std::vector<std::thread> callers;
  for (size_t c = 0; c < counts.size(); ++c)
    callers.emplace_back([&, c] {
      for (int round = 0; round < 20; ++round)
        parallel_for(0, 50'000, [&](std::int64_t i) { ++counts[c][static_cast<size_t>(i)]; });
    });
  for (std::thread& t : callers) t.join();
  for (const std::vector<int>& count : counts)
    for (size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i], 20) << i;
  set_worker_thread_count(threads);
}

}  // namespace parallel_test
}  // namespace radrecon
