#pragma once
// The one parallel loop of the project. Iterations are independent and write disjoint outputs,
// so results never depend on the number of threads; reductions are done by the caller over
// per-index results in a fixed order.

#include <cstdint>

namespace radrecon {

/// Ranges shorter than this run on the calling thread: waking the team costs more than they do.
inline constexpr std::int64_t kParallelMinIterations = 512;

/// Calls body(i) for every i in [begin, end), on all threads (OpenMP, chunks of 256 handed out
/// dynamically).
template <typename Body>
void parallel_for(std::int64_t begin, std::int64_t end, Body&& body) {
#pragma omp parallel for schedule(dynamic, 256) if (end - begin >= kParallelMinIterations)
  for (std::int64_t i = begin; i < end; ++i) body(i);
}

}  // namespace radrecon
