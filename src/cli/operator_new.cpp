// radrecon's global operator new: malloc's memory, with the large allocations advised onto
// transparent huge pages (core/allocator.h). Every other form of new (arrays, nothrow) reaches
// this one through the standard library's defaults, and every delete is the library's free():
// memory may pass between the program and its plugins either way. Left out of sanitized builds,
// whose own operator new tracks allocations.

#include <cstdlib>
#include <new>

#include "core/allocator.h"

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

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

#endif
