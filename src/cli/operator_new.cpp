// radrecon's global operator new: malloc's memory, with the large allocations advised onto
// transparent huge pages (core/allocator.h). Every other form of new (arrays, nothrow) in the
// program reaches this one through the standard library's defaults, and the library's delete is
// free(): memory may pass between the program and its plugins (which link the shared libstdc++
// and allocate through its operator new, malloc too) either way. Left out of sanitized builds
// (CMakeLists.txt), whose runtime pairs its own operator new with its own delete.

#include <cstdlib>
#include <new>

#include "core/allocator.h"

void* operator new(std::size_t bytes) {
  if (bytes == 0) bytes = 1;
  while (true) {
    if (void* p = std::malloc(bytes)) {
      if (bytes >= radrecon::kHugePageAllocationBytes) radrecon::advise_huge_pages(p, bytes);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) throw std::bad_alloc();
    handler();
  }
}
