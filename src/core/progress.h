#pragma once
// Progress of a long stage on stderr: on a terminal one line rewritten in place, elsewhere (a
// log file, a pipe) a plain line at most every kProgressInterval; nothing when quiet. Not
// thread-safe: one thread reports at a time (the loops report between their parallel batches;
// `radrecon paper`'s two concurrent stages under a mutex).

#include <chrono>
#include <optional>
#include <string>

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

}  // namespace radrecon
