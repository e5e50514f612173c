#pragma once
// The one parallel loop of the project. Iterations are independent and write disjoint outputs,
// so results never depend on the number of threads; reductions are done by the caller over
// per-index results in a fixed order.

#include <cstdint>

namespace radrecon {

/// Calls body(i) for every i in [begin, end), on all threads (OpenMP, static schedule).
template <typename Body>
void parallel_for(std::int64_t begin, std::int64_t end, Body&& body) {
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = begin; i < end; ++i) body(i);
}

}  // namespace radrecon
