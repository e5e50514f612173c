#pragma once
// Progress of a long stage on stderr: on a terminal one line rewritten in place, elsewhere (a
// log file, a pipe) a plain line at most every kProgressInterval; nothing when quiet. Not
// thread-safe: one thread reports at a time (the loops report between their parallel batches;
// `radrecon paper`'s two concurrent stages under a mutex).

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace radrecon {

/// At most one report in this time.
inline constexpr std::chrono::seconds kProgressInterval{2};

class Progress {
 public:
  /// `label` starts every line ("interpolate", "render"); quiet: reports nothing.
  Progress(std::string label, bool quiet);
  /// Ends an updating line with a newline.
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports the fraction done (0..1) of `what` with the time elapsed and the time left, if the
  /// last report is kProgressInterval old. The time left is judged from `stage_start`, when `what`
  /// began (default: when the progress did; a later stage of a longer run gives its own).
  void update(double fraction, const std::string& what,
              std::optional<std::chrono::steady_clock::time_point> stage_start = std::nullopt);
  /// Reports `what` (a stage whose share done is unknown: "refinement pass 3, 1200 links") with
  /// the time elapsed, as update() does.
  void note(const std::string& what);
  /// Ends an updating line, so that what follows starts a line of its own.
  void done();

 private:
  std::string label_;
  bool quiet_, terminal_;
  bool line_open_ = false;  ///< an updating line is on the terminal
  std::chrono::steady_clock::time_point start_, last_;
};

/// ConvergencePace judges by the pace from this time on (below).
inline constexpr std::chrono::seconds kConvergencePaceAfter{10};

/// The share of time done of a run that converges, for Progress::update(): an iteration that
/// drives a residual down to a target. A run whose residual falls geometrically at a steady pace
/// is a straight line in log(residual) against time; its later iterations often go slower, which
/// a share by log(residual) alone (the way done) took for speed (a solve said "about 17 s left"
/// from 39 s to 112 s). Here the time left is the log-distance to the target at the pace of the
/// last half of the run so far, from kConvergencePaceAfter on (before it, the first iterations,
/// often the slowest, would rule the pace: by the way done alone).
class ConvergencePace {
 public:
  explicit ConvergencePace(double target) : log_target_(std::log(target)) {}
  /// Records the residual (in (0, 1)) now and returns the share done, in (0, 1).
  double share_done(double residual);
  /// The same at `seconds` since the run began (non-decreasing from call to call).
  double share_done_at(double residual, double seconds);

 private:
  double log_target_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::vector<std::pair<double, double>> samples_;  ///< (seconds since start, log residual)
};

}  // namespace radrecon
