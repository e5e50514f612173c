// The parallel loops and the pool they run on: every index once, whatever the threads, from
// nested loops and from several calling threads at once, and an exception thrown by an
// iteration reaches the caller (it must not terminate the program from inside a worker).

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/thread_pool.h"
#include "core/once.h"
#include "core/parallel.h"

namespace radrecon {
namespace parallel_test {

/// Sets the loops' thread count for a scope, restoring it however the scope ends.
class Threads {
 public:
  explicit Threads(int n) : before_(worker_thread_count()) { set_worker_thread_count(n); }
  ~Threads() { set_worker_thread_count(before_); }
  void set(int n) { set_worker_thread_count(n); }

 private:
  int before_;
};

TEST(ThreadPool, EveryParticipantRunsOnceEachOnItsOwnThread) {
  Threads threads(1);
  for (int t : {1, 2, 3, 5}) {
    threads.set(t);
    for (int round = 0; round < 50; ++round) {
      std::mutex mutex;
      std::vector<int> calls(static_cast<size_t>(t), 0);
      std::vector<std::thread::id> ids;
      auto job = [&](int participant) {
        std::lock_guard<std::mutex> lock(mutex);
        ++calls.at(static_cast<size_t>(participant));
        ids.push_back(std::this_thread::get_id());
      };
      run_on_threads(t, ThreadJob(job));
      for (int p = 0; p < t; ++p) ASSERT_EQ(calls[static_cast<size_t>(p)], 1) << t << " threads, participant " << p;
      std::sort(ids.begin(), ids.end());
      EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end()) << "two participants on one thread";
    }
  }
}

TEST(ParallelFor, ChunksRunOnSeveralThreadsAtOnce) {
  // The first chunk waits until a chunk has started on another thread: it can only end if two
  // threads take part (bounded: a failure, not a hang, if they never do).
  Threads threads(2);
  std::atomic<bool> second_started{false};
  std::atomic<bool> waited_out{false};
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> on_workers{0};
  parallel_for(0, 4 * kParallelChunk, [&](std::int64_t i) {
    if (std::this_thread::get_id() != caller) ++on_workers;
    if (i >= kParallelChunk) second_started = true;
    if (i != 0) return;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!second_started && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    waited_out = !second_started;
  });
  EXPECT_FALSE(waited_out.load());
  EXPECT_GT(on_workers.load(), 0);
}

TEST(ParallelFor, VisitsEveryIndexOnceOnOneTwoAndFiveThreads) {
  Threads threads(1);
  for (int t : {1, 2, 5}) {
    threads.set(t);
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
}

TEST(ParallelFor, AnExceptionFromAnIterationIsRethrownToTheCaller) {
  Threads threads(2);
  // Thrown on a worker: the caller's iterations wait (bounded) until a worker has started one.
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> worker_started{false};
  EXPECT_THROW(parallel_for(0, 100'000,
                            [&](std::int64_t) {
                              if (std::this_thread::get_id() == caller) {
                                const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
                                while (!worker_started && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
                                return;
                              }
                              worker_started = true;
                              throw std::range_error("on a worker");
                            }),
               std::range_error);
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
}

TEST(ParallelFor, NestedLoopsAndSeveralCallersEachVisitEveryIndexOnce) {
  Threads threads(3);
  // A loop inside a loop's iteration runs on that iteration's thread.
  std::vector<std::atomic<int>> seen(64 * 1000);
  std::atomic<int> elsewhere{0};
  parallel_for_coarse(0, 64, [&](std::int64_t outer) {
    const std::thread::id outer_thread = std::this_thread::get_id();
    parallel_for(0, 1000, [&](std::int64_t inner) {
      ++seen[static_cast<size_t>(outer * 1000 + inner)];
      if (std::this_thread::get_id() != outer_thread) ++elsewhere;
    });
  });
  EXPECT_EQ(elsewhere.load(), 0);
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
}

}  // namespace parallel_test
}  // namespace radrecon

namespace radrecon {
namespace made_once_test {

TEST(MadeOnce, EveryThreadGetsTheOneValueMadeOnce) {
  MadeOnce<int> value;
  std::atomic<int> made{0};
  std::vector<const int*> seen(8, nullptr);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < seen.size(); ++t)
    threads.emplace_back([&, t] {
      seen[t] = &value.get([&] {
        ++made;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the others arrive meanwhile
        return std::make_unique<int>(42);
      });
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(made.load(), 1);
  for (const int* p : seen) {
    ASSERT_EQ(p, seen[0]);
    EXPECT_EQ(*p, 42);
  }
}

TEST(MadeOnce, AThrowReachesEveryCallerAndIsNotRetried) {
  // std::call_once would run the maker again, and libstdc++'s may hang there (GCC bug 66146).
  MadeOnce<int> value;
  int made = 0;
  const auto make = [&]() -> std::unique_ptr<int> {
    ++made;
    throw std::runtime_error("cannot make it");
  };
  for (int k = 0; k < 3; ++k) EXPECT_THROW(value.get(make), std::runtime_error);
  EXPECT_EQ(made, 1);
}

}  // namespace made_once_test
}  // namespace radrecon
