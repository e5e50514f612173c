#pragma once
// Solutions on one worker thread and on several, compared bit for bit: results must not depend
// on the number of threads.

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

#include "core/thread_pool.h"
#include "solver/solution.h"

namespace radrecon::testing_support {

/// `solve()` run on one worker thread, then on the pool's count (at least 2); the pool left as
/// it was.
template <typename Solve>
std::pair<Solution, Solution> solved_on_one_and_many_threads(const Solve& solve) {
  const int threads = worker_thread_count();
  set_worker_thread_count(1);
  Solution one = solve();
  set_worker_thread_count(std::max(2, threads));
  Solution many = solve();
  set_worker_thread_count(threads);
  return {std::move(one), std::move(many)};
}

/// Every element's radiosity, every channel, and the escaped power: the same bits.
inline void expect_same_bits(const Solution& a, const Solution& b) {
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (size_t s = 0; s < a.surfaces.size(); ++s) {
    ASSERT_EQ(a.surfaces[s].elements.size(), b.surfaces[s].elements.size());
    for (size_t e = 0; e < a.surfaces[s].elements.size(); ++e)
      ASSERT_TRUE((a.surfaces[s].elements[e].radiosity_w_m2 == b.surfaces[s].elements[e].radiosity_w_m2).all())
          << a.surfaces[s].name << " element " << e;
  }
  EXPECT_TRUE((a.stats.escaped_w == b.stats.escaped_w).all());
}

}  // namespace radrecon::testing_support
