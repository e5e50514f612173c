// The parallel loops: every index once, whatever the threads, and an exception thrown by an
// iteration reaches the caller (it must not terminate the program from inside OpenMP).

#include <gtest/gtest.h>
#include <omp.h>

#include <new>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"

namespace radrecon {
namespace parallel_test {

TEST(ParallelFor, VisitsEveryIndexOnceOnOneAndTwoThreads) {
  const int threads = omp_get_max_threads();
  for (int t : {1, 2}) {
    omp_set_num_threads(t);
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
  omp_set_num_threads(threads);
}

TEST(ParallelFor, AnExceptionFromAnIterationIsRethrownToTheCaller) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
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
  omp_set_num_threads(threads);
}

}  // namespace parallel_test
}  // namespace radrecon
