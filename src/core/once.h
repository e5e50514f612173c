#pragma once
// A value made once, on first need, and shared between threads.

#include <atomic>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>

#include "core/check.h"

namespace radrecon {

/// A value made by the first caller of get() (the others wait for it, then share it). If making
/// it throws, that caller and every later one get the exception. Not std::call_once: after its
/// callable throws, libstdc++'s may block the next caller for ever (GCC bug 66146).
template <typename T>
class MadeOnce {
 public:
  /// The value, made by make() (returning a std::unique_ptr<T>) if this is the first call.
  template <typename Make>
  const T& get(Make&& make) const {
    if (!done_.load(std::memory_order_acquire)) {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!started_) {
        started_ = true;
        lock.unlock();
        std::unique_ptr<T> made;
        std::exception_ptr error;
        try {
          made = make();
        } catch (...) {
          error = std::current_exception();
        }
        lock.lock();
        value_ = std::move(made);
        error_ = error;
        done_.store(true, std::memory_order_release);
        made_.notify_all();
      } else {
        made_.wait(lock, [&] { return done_.load(std::memory_order_relaxed); });
      }
    }
    if (error_) std::rethrow_exception(error_);
    RR_CHECK(value_ != nullptr, "a value made once read after its release()");
    return *value_;
  }

  /// Frees the value: once no caller will use it again.
  void release() {
    const std::lock_guard<std::mutex> lock(mutex_);
    value_.reset();
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable made_;
  mutable bool started_ = false;
  mutable std::atomic<bool> done_{false};
  mutable std::unique_ptr<T> value_;
  mutable std::exception_ptr error_;
};

}  // namespace radrecon
