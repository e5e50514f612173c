#pragma once
// The one parallel loop of the project, alone or with per-thread scratch. Iterations are
// independent and write disjoint outputs, so results never depend on the number of threads;
// reductions are done by the caller over per-index results in a fixed order.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/thread_pool.h"

namespace radrecon {

/// Ranges shorter than this run on the calling thread: waking the team costs more than they do.
inline constexpr std::int64_t kParallelMinIterations = 512;
/// Iterations handed out to a thread at a time.
inline constexpr std::int64_t kParallelChunk = 256;

/// An exception thrown by an iteration (std::bad_alloc, a ReconstructionError) must not leave a
/// worker thread, which would terminate the program: the first one is kept, the remaining
/// iterations are skipped, and it is rethrown on the calling thread after the loop.
class LoopException {
 public:
  template <typename F>
  void run(F&& f) {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      f();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::mutex mutex_;
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};  // a hint to skip work; error_ is the truth
};

/// Runs chunk(c) for every c in [0, chunks), each once, on up to `threads` threads (the pool's,
/// core/thread_pool.h) that claim chunks one at a time; with a Scratch type, each participating
/// thread default-constructs one before its first chunk and passes it to each: chunk(c, scratch).
/// An exception from chunk is rethrown after the loop (LoopException).
template <typename Scratch = void, typename Chunk>
void run_chunks(std::int64_t chunks, int threads, Chunk&& chunk) {
  LoopException error;
  std::atomic<std::int64_t> next{0};
  const auto claim = [&] { return next.fetch_add(1, std::memory_order_relaxed); };
  auto job = [&](int) {
    if constexpr (std::is_void_v<Scratch>) {
      for (std::int64_t c = claim(); c < chunks; c = claim()) error.run([&] { chunk(c); });
    } else {
      std::optional<Scratch> scratch;
      error.run([&] { scratch.emplace(); });
      if (!scratch) return;
      for (std::int64_t c = claim(); c < chunks; c = claim()) error.run([&] { chunk(c, *scratch); });
    }
  };
  run_on_threads(static_cast<int>(std::min<std::int64_t>(threads, std::max<std::int64_t>(chunks, 1))), ThreadJob(job));
  error.rethrow();
}

/// Calls body(i) for every i in [begin, end), on all threads (chunks of kParallelChunk handed out
/// dynamically). An exception from body is rethrown after the loop (LoopException).
template <typename Body>
void parallel_for(std::int64_t begin, std::int64_t end, Body&& body) {
  const std::int64_t chunks = end > begin ? (end - begin + kParallelChunk - 1) / kParallelChunk : 0;
  run_chunks(chunks, end - begin >= kParallelMinIterations ? worker_thread_count() : 1, [&](std::int64_t c) {
    // one exception guard a chunk: the iterations inside run as a plain loop
    const std::int64_t lo = begin + c * kParallelChunk, hi = std::min(end, lo + kParallelChunk);
    for (std::int64_t i = lo; i < hi; ++i) body(i);
  });
}

/// parallel_for for iterations of widely varying cost, each far more than handing it out (a
/// receiving element's gathering from a shot: microseconds to milliseconds): chunks of `grain`
/// iterations, in parallel from two chunks on.
template <typename Body>
void parallel_for_grained(std::int64_t begin, std::int64_t end, std::int64_t grain, Body&& body) {
  grain = std::max<std::int64_t>(grain, 1);
  const std::int64_t chunks = end > begin ? (end - begin + grain - 1) / grain : 0;
  run_chunks(chunks, worker_thread_count(), [&](std::int64_t c) {
    const std::int64_t lo = begin + c * grain, hi = std::min(end, lo + grain);
    for (std::int64_t i = lo; i < hi; ++i) body(i);
  });
}

/// parallel_for for iterations that each cost far more than waking the team (a link's form
/// factor by cubature, a block of receivers): handed out one at a time, in parallel from two on.
template <typename Body>
void parallel_for_coarse(std::int64_t begin, std::int64_t end, Body&& body) {
  run_chunks(std::max<std::int64_t>(end - begin, 0), worker_thread_count(), [&](std::int64_t c) { body(begin + c); });
}

/// parallel_for_with_scratch (below) with chunks of `grain` iterations, in parallel from `least`
/// iterations on: for iterations that each cost far more than handing them out (a run of
/// natural-neighbour queries).
template <typename Scratch, typename Body>
void parallel_for_with_scratch(std::int64_t begin, std::int64_t end, std::int64_t grain, std::int64_t least,
                               Body&& body) {
  grain = std::max<std::int64_t>(grain, 1);
  const std::int64_t chunks = end > begin ? (end - begin + grain - 1) / grain : 0;
  run_chunks<Scratch>(chunks, end - begin >= least ? worker_thread_count() : 1, [&](std::int64_t c, Scratch& scratch) {
    const std::int64_t lo = begin + c * grain, hi = std::min(end, lo + grain);
    for (std::int64_t i = lo; i < hi; ++i) body(i, scratch);
  });
}

/// parallel_for with one Scratch object per thread, default-constructed when the thread joins
/// the loop and passed to every iteration that thread runs: body(i, scratch). Buffers in it grow
/// once per thread and call, never per iteration, and nothing outlives the call (no
/// thread_local; after pbrt's ThreadLocal beside ParallelFor). A body must overwrite what it
/// reads from the scratch before using it, so that results never depend on which thread ran
/// which iteration. Same schedule and threshold as parallel_for.
template <typename Scratch, typename Body>
void parallel_for_with_scratch(std::int64_t begin, std::int64_t end, Body&& body) {
  parallel_for_with_scratch<Scratch>(begin, end, kParallelChunk, kParallelMinIterations, std::forward<Body>(body));
}

}  // namespace radrecon
