#pragma once
// Included by each benchmark program: freed memory kept for reuse, as radrecon's main keeps it
// (core/allocator.h). Else the large blocks a run allocates (a fit's matrices, the solvers'
// growing vectors, a raster's faces) are mapped and unmapped each time, and the page faults are
// what is measured. (radrecon's operator new, which also advises huge pages, is not linked in.)

#include "core/allocator.h"

namespace radrecon::bench {

[[maybe_unused]] inline const bool kFreedMemoryKept = (keep_freed_memory(), true);

}  // namespace radrecon::bench
