#pragma once
// The one per-thread scratch pattern of reconstruct/: parallel_for (core/parallel.h) with one
// Scratch object per thread, default-constructed when the thread joins the loop and passed to
// every iteration that thread runs. Buffers in it grow once per thread and call, never per
// iteration, and nothing outlives the call (no thread_local). Same schedule and threshold as
// parallel_for. A body must overwrite what it reads from the scratch before using it, so that
// results never depend on which thread ran which iteration.
// (It belongs beside parallel_for in core/parallel.h, as pbrt's ThreadLocal beside ParallelFor.)

#include <cstdint>

#include "core/parallel.h"

namespace radrecon {

/// Calls body(i, scratch) for every i in [begin, end), scratch being the calling thread's Scratch.
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
