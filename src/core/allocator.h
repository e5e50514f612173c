#pragma once
// How the program's allocator treats freed memory.

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

}  // namespace radrecon
