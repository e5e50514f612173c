#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace radrecon {

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), quiet_(quiet), terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() { done(); }

void Progress::done() {
  if (line_open_) std::fputc('\n', stderr);
  line_open_ = false;
}

void Progress::update(double fraction, const std::string& what,
                      std::optional<std::chrono::steady_clock::time_point> stage_start) {
  const auto now = std::chrono::steady_clock::now();
  if (quiet_ || fraction <= 0 || fraction >= 1 || now - last_ < kProgressInterval) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double stage = std::chrono::duration<double>(now - stage_start.value_or(start_)).count();
  std::fprintf(stderr, "%s%s: %.0f%% of %s, %.0f s elapsed, about %.0f s left%s", terminal_ ? "\r" : "",
               label_.c_str(), 100 * fraction, what.c_str(), elapsed, stage * (1 - fraction) / fraction,
               terminal_ ? "\033[K" : "\n");
  std::fflush(stderr);
  line_open_ = terminal_;
}

void Progress::note(const std::string& what) {
  const auto now = std::chrono::steady_clock::now();
  if (quiet_ || now - last_ < kProgressInterval) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "%s%s: %s, %.0f s elapsed%s", terminal_ ? "\r" : "", label_.c_str(), what.c_str(), elapsed,
               terminal_ ? "\033[K" : "\n");
  std::fflush(stderr);
  line_open_ = terminal_;
}

}  // namespace radrecon
