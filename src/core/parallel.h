#pragma once
// The one parallel loop of the project, alone or with per-thread scratch. Iterations are
// independent and write disjoint outputs, so results never depend on the number of threads;
// reductions are done by the caller over per-index results in a fixed order.

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

/// parallel_for with one Scratch object per thread, default-constructed when the thread joins
/// the loop and passed to every iteration that thread runs: body(i, scratch). Buffers in it grow
/// once per thread and call, never per iteration, and nothing outlives the call (no
/// thread_local; after pbrt's ThreadLocal beside ParallelFor). A body must overwrite what it
/// reads from the scratch before using it, so that results never depend on which thread ran
/// which iteration. Same schedule and threshold as parallel_for.
template <typename Scratch, typename Body>
void parallel_for_with_scratch(std::int64_t begin, std::int64_t end, Body&& body) {
#pragma omp parallel if (end - begin >= kParallelMinIterations)
  {
    Scratch scratch{};
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = begin; i < end; ++i) body(i, scratch);
  }
}

}  // namespace radrecon
