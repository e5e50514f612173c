#pragma once
// The one parallel loop of the project, alone or with per-thread scratch. Iterations are
// independent and write disjoint outputs, so results never depend on the number of threads;
// reductions are done by the caller over per-index results in a fixed order.

#include <atomic>
#include <cstdint>
#include <exception>
#include <optional>

namespace radrecon {

/// Ranges shorter than this run on the calling thread: waking the team costs more than they do.
inline constexpr std::int64_t kParallelMinIterations = 512;

/// An exception thrown by an iteration (std::bad_alloc, a ReconstructionError) must not leave an
/// OpenMP region, which would terminate the program: the first one is kept, the remaining
/// iterations are skipped, and it is rethrown on the calling thread after the loop.
class LoopException {
 public:
  template <typename F>
  void run(F&& f) {
    if (failed_.load(std::memory_order_relaxed)) return;
    try {
      f();
    } catch (...) {
#pragma omp critical(radrecon_loop_exception)
      if (!error_) error_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
    }
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  std::exception_ptr error_;
  std::atomic<bool> failed_{false};  // a hint to skip work; error_ is the truth
};

/// Calls body(i) for every i in [begin, end), on all threads (OpenMP, chunks of 256 handed out
/// dynamically). An exception from body is rethrown after the loop (LoopException).
template <typename Body>
void parallel_for(std::int64_t begin, std::int64_t end, Body&& body) {
  LoopException error;
#pragma omp parallel for schedule(dynamic, 256) if (end - begin >= kParallelMinIterations)
  for (std::int64_t i = begin; i < end; ++i) error.run([&] { body(i); });
  error.rethrow();
}

/// parallel_for with one Scratch object per thread, default-constructed when the thread joins
/// the loop and passed to every iteration that thread runs: body(i, scratch). Buffers in it grow
/// once per thread and call, never per iteration, and nothing outlives the call (no
/// thread_local; after pbrt's ThreadLocal beside ParallelFor). A body must overwrite what it
/// reads from the scratch before using it, so that results never depend on which thread ran
/// which iteration. Same schedule and threshold as parallel_for.
template <typename Scratch, typename Body>
void parallel_for_with_scratch(std::int64_t begin, std::int64_t end, Body&& body) {
  LoopException error;
#pragma omp parallel if (end - begin >= kParallelMinIterations)
  {
    std::optional<Scratch> scratch;
    error.run([&] { scratch.emplace(); });
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = begin; i < end; ++i)
      if (scratch) error.run([&] { body(i, *scratch); });
  }
  error.rethrow();
}

}  // namespace radrecon
