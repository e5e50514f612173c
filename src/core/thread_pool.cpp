#include "core/thread_pool.h"

#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace radrecon {

namespace {

/// How long an idle worker, or a caller waiting for the workers, spins before it sleeps:
/// consecutive loops (a batch of queries after a batch) then start without a wake-up's
/// latency, and a long pause costs a sleeping thread, not a spinning core.
constexpr std::chrono::microseconds kIdleSpin{50};
/// More threads than this are not made, whatever OMP_NUM_THREADS says.
constexpr int kMaxThreads = 256;

/// True on the pool's workers, and on a caller while it runs job(0): a loop started there runs
/// on its own thread alone.
thread_local bool t_in_job = false;

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// Spins until done() or kIdleSpin has passed; returns done().
template <typename Done>
bool spin_until(Done&& done) {
  const auto until = std::chrono::steady_clock::now() + kIdleSpin;
  for (;;) {
    for (int k = 0; k < 64; ++k) {
      if (done()) return true;
      cpu_relax();
    }
    if (std::chrono::steady_clock::now() >= until) return done();
  }
}

class Pool {
 public:
  pid_t pid() const { return pid_; }

  /// False, without running anything, if another thread's job holds the pool.
  bool try_run(int threads, const ThreadJob& job) {
    std::unique_lock<std::mutex> hold(run_mutex_, std::try_to_lock);
    if (!hold.owns_lock()) return false;
    // Workers are made as jobs first need them; a new one has seen every job so far. A thread
    // the system refuses leaves the job to fewer.
    for (; workers_ < threads - 1 && !spawn_failed_; ++workers_) {
      try {
        std::thread([this, w = workers_ + 1, seen = generation_.load()] { work(w, seen); }).detach();
      } catch (...) {  // std::system_error, std::bad_alloc: not tried again
        spawn_failed_ = true;
        break;
      }
    }
    const int helpers = std::min(threads - 1, workers_);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      job_ = &job;
      helpers_ = helpers;
      pending_.store(helpers, std::memory_order_relaxed);
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    // The helpers are waited for however job(0) ends: they may be using the caller's frame.
    struct WaitForHelpers {
      Pool& pool;
      ~WaitForHelpers() {
        t_in_job = false;
        const auto finished = [&] { return pool.pending_.load(std::memory_order_acquire) == 0; };
        if (!spin_until(finished)) {
          std::unique_lock<std::mutex> lock(pool.mutex_);
          pool.done_.wait(lock, finished);
        }
      }
    } wait{*this};
    t_in_job = true;
    job(0);
    return true;
  }

 private:
  void work(int index, std::uint64_t seen) {
    t_in_job = true;
    bool spin = true;  // not after a job without this worker: it would spin for every small loop
    for (;;) {
      const auto published = [&] { return generation_.load(std::memory_order_acquire) != seen; };
      if (spin) spin_until(published);
      const ThreadJob* job = nullptr;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, published);
        seen = generation_.load(std::memory_order_relaxed);
        if (index <= helpers_) job = job_;
      }
      spin = job != nullptr;
      if (!job) continue;  // a job of fewer threads
      (*job)(index);
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);  // the caller tests `pending_` under it
        done_.notify_one();
      }
    }
  }

  const pid_t pid_ = getpid();
  bool spawn_failed_ = false;
  int workers_ = 0;  // detached threads: the pool lives as long as the process, its workers asleep when idle
  std::mutex run_mutex_;              // one job at a time
  std::mutex mutex_;                  // guards job_ and helpers_, and orders the waits
  std::condition_variable wake_, done_;
  const ThreadJob* job_ = nullptr;
  int helpers_ = 0;  // workers 1..helpers_ take part in the current job
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<int> pending_{0};
};

int read_thread_count() {
  if (const char* env = std::getenv("OMP_NUM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && n > 0) return static_cast<int>(std::min<long>(n, kMaxThreads));
  }
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof cpus, &cpus) == 0) return std::clamp(CPU_COUNT(&cpus), 1, kMaxThreads);
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, kMaxThreads);
}

// The pool, made on first use and never destroyed (its workers sleep until the process ends).
// A child of fork() has none of its parent's threads: it makes a pool of its own (the parent's
// is left as it is, its mutexes perhaps held by threads the child does not have).
std::atomic<Pool*> g_pool{nullptr};

Pool* pool() {
  Pool* p = g_pool.load(std::memory_order_acquire);
  if (p && p->pid() == getpid()) return p;
  Pool* fresh = new Pool;  // no thread yet: workers are made by the first job that needs them
  if (g_pool.compare_exchange_strong(p, fresh, std::memory_order_acq_rel)) return fresh;
  delete fresh;  // another thread of this process made one first: `p` is now it
  return p;
}

std::atomic<int> g_thread_count{0};  // 0: not yet read

}  // namespace

int worker_thread_count() {
  int n = g_thread_count.load(std::memory_order_relaxed);
  if (n == 0) {
    const int read = read_thread_count();
    // From 0 only: a set_worker_thread_count() meanwhile wins.
    return g_thread_count.compare_exchange_strong(n, read, std::memory_order_relaxed) ? read : n;
  }
  return n;
}

void set_worker_thread_count(int threads) {
  g_thread_count.store(std::clamp(threads, 1, kMaxThreads), std::memory_order_relaxed);
}

LoopsOnThisThread::LoopsOnThisThread() : was_(t_in_job) { t_in_job = true; }
LoopsOnThisThread::~LoopsOnThisThread() { t_in_job = was_; }

bool enter_background_scheduling() {
#ifdef SCHED_IDLE
  sched_param param{};
  param.sched_priority = 0;
  return pthread_setschedparam(pthread_self(), SCHED_IDLE, &param) == 0;
#else
  return false;
#endif
}

void run_on_threads(int threads, const ThreadJob& job) {
  threads = std::min(threads, worker_thread_count());
  if (threads <= 1 || t_in_job || !pool()->try_run(threads, job)) {
    const LoopsOnThisThread alone;
    job(0);
  }
}

}  // namespace radrecon
