#include "core/allocator.h"

#include <malloc.h>

#include <limits>

namespace radrecon {

void keep_freed_memory() {
  constexpr int kMmapThresholdBytes = 32 << 20;  // glibc's largest on 64-bit systems
  mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

}  // namespace radrecon
