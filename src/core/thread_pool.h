#pragma once
// The project's worker threads (core/parallel.h's loops run on them): one pool, made on first
// use, that runs a job on several threads at once. Idle workers spin for some tens of
// microseconds, for the loop that often follows, and then sleep: OpenMP's (libgomp's) spun for
// milliseconds after every loop, which on this 2-core machine slowed the serial work that
// followed (docs/benchmarks.md, "Worker threads of our own").

#include <cstdint>

namespace radrecon {

/// The threads a parallel loop uses, the calling thread included: OMP_NUM_THREADS if it starts
/// with a positive integer (the variable OpenMP reads: scripts and tests that set it keep
/// working), else the CPUs this process may run on; or what set_worker_thread_count() set.
int worker_thread_count();

/// Makes later loops use `threads` threads (at least 1), the pool growing to it if need be: for
/// tests that check that results do not depend on the number of threads.
void set_worker_thread_count(int threads);

/// A job for run_on_threads(): a callable taking the participant's index, by reference.
class ThreadJob {
 public:
  template <typename F>
  explicit ThreadJob(F& f) : object_(&f), call_([](void* o, int t) { (*static_cast<F*>(o))(t); }) {}
  void operator()(int participant) const { call_(object_, participant); }

 private:
  void* object_;
  void (*call_)(void*, int);
};

/// Calls job(0) on the calling thread and job(1) ... job(threads - 1) on the pool's workers at
/// the same time; returns when every call has returned, their writes visible to the caller.
/// Only job(0) is sure to run: from inside a job (a nested loop), while another thread's job
/// holds the pool, or with threads <= 1, it runs alone. So a job must share its work out
/// dynamically (each participant claiming chunks from a counter until none is left), and must
/// not throw (core/parallel.h's LoopException catches what its iterations throw).
void run_on_threads(int threads, const ThreadJob& job);

/// While it lives, the loops started on the calling thread run on it alone, as a job's nested
/// loops do: for background work that must not hold the pool (a thread that may wait long for a
/// core would keep the pool's workers from everyone else's loops meanwhile).
class LoopsOnThisThread {
 public:
  LoopsOnThisThread();
  ~LoopsOnThisThread();
  LoopsOnThisThread(const LoopsOnThisThread&) = delete;
  LoopsOnThisThread& operator=(const LoopsOnThisThread&) = delete;

 private:
  bool was_;
};

/// Puts the calling thread in the background for good (Linux's SCHED_IDLE: it runs only on a
/// core that would otherwise be idle); false where the system refuses, the thread then as it was.
/// For good: an unprivileged thread may not come back (RLIMIT_NICE, 0 by default), so whatever
/// it does must never be waited for by a busy thread. Its results are the same either way: only
/// when it runs changes.
bool enter_background_scheduling();

}  // namespace radrecon
