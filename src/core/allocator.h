#pragma once
// How the program's allocator treats freed memory.

#include <cstddef>

namespace radrecon {

/// glibc's allocator returns freed memory to the system eagerly: a block of 128 KiB or more is
/// mapped for itself and unmapped when freed, and the heap's free top is trimmed beyond 128 KiB.
/// The solvers free and grow vectors of links, waves and receivers pass after pass, and the RBFs
/// with barriers allocate a matrix of some 170 KB per fit, thousands of fits; each page taken
/// again costs a page fault, expensive under virtualisation: quadtree:1000 on the Cornell box
/// spent a third of its time there (docs/benchmarks.md). Freed memory is kept for reuse instead,
/// for a few percent more peak memory (92 MiB against 88 there). For programs (radrecon's main,
/// the benchmarks); the Python module leaves its host's allocator alone.
void keep_freed_memory();

/// Allocations of this many bytes or more are backed by transparent huge pages where the
/// system offers them (advise_huge_pages()): a page fault costs some 10-20 us on this virtual
/// machine, a 4 KiB page's share of a huge page's fault some 0.3 us (docs/benchmarks.md). Smaller
/// ones are left alone: a huge page is zeroed whole however little of it is used, which made
/// the small runs slower when the whole heap was advised (W1: 37 against 34 ms).
inline constexpr std::size_t kHugePageAllocationBytes = std::size_t{2} << 20;

/// Advises the kernel to back the 2 MiB-aligned pages inside [p, p + bytes) with huge pages
/// (madvise MADV_HUGEPAGE); nothing where the system has none, or the range holds no such page.
/// radrecon's operator new (cli/operator_new.cpp) calls it for allocations of
/// kHugePageAllocationBytes or more; the memory stays malloc's, freed by free().
void advise_huge_pages(void* p, std::size_t bytes);

}  // namespace radrecon
