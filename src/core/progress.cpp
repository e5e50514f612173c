#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
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

double ConvergencePace::share_done(double residual) {
  return share_done_at(residual, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

double ConvergencePace::share_done_at(double residual, double now) {
  const double log_r = std::log(residual);
  samples_.emplace_back(now, log_r);
  const double by_way = std::clamp(log_r / log_target_, 1e-6, 1 - 1e-6);  // the way done, in log(residual)
  // The pace since the first sample of the last half of the run.
  const auto half = std::lower_bound(samples_.begin(), samples_.end(), 0.5 * now,
                                     [](const std::pair<double, double>& s, double t) { return s.first < t; });
  const double dt = now - half->first, dlog = log_r - half->second;
  // Early on, the first iterations (often the slowest: the first shots of a radiosity solve)
  // would rule the pace: the way done until kConvergencePaceAfter.
  if (now < kConvergencePaceAfter.count() || !(dt > 0 && dlog < 0)) return by_way;
  const double left = (log_target_ - log_r) / (dlog / dt);  // seconds at that pace
  if (!(left >= 0)) return by_way;
  return std::clamp(now / (now + left), 1e-6, 1 - 1e-6);
}

}  // namespace radrecon
