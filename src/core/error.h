#pragma once
// radrecon's three kinds of error:
//   - bad user input (a malformed file, a bad option): a UserError that carries where the
//     problem is (file, line, field or option, passed down by the caller: library code never
//     names a command-line option), ending the program with exit code kUserErrorExitCode;
//   - a result that cannot be computed (too few samples for a method, a query outside the hull):
//     a returned value (std::optional, Result in result.h, NaN), not an exception;
//   - a broken internal invariant: an RR_CHECK (check.h), in every build, printing its operands.

#include <stdexcept>
#include <string>
#include <vector>

namespace radrecon {

/// Exit code for every refused input, as the command-line contract fixes it.
inline constexpr int kUserErrorExitCode = 2;
/// Exit code when memory runs out (std::bad_alloc): the request was too large for the machine.
inline constexpr int kOutOfMemoryExitCode = 3;

class UserError : public std::runtime_error {
 public:
  /// `where` names the file and the field or line ("scene.json: surfaces[2].corners"),
  /// `what` says what is wrong with it.
  UserError(const std::string& where, const std::string& what);
  explicit UserError(const std::string& what);
};

/// `said`, a library's words for a write that failed (GDAL's "Write failed, disk full?", libtiff's
/// "Write error at scanline 40"), with the system's reason after it, " (File too large)", when
/// errno, read right after the library returns, is one that only a failing write or close sets
/// (no space, file too large, disk quota, I/O error) and `said` does not say it already. The
/// caller sets errno to 0 before calling the library, so that an earlier call's errno is not
/// taken for the reason.
std::string with_failed_write_reason(const std::string& said);

/// Says a warning to the user: "radrecon: warning: MESSAGE" on stderr, or, while a
/// WarningCollector lives on the calling thread, into it (the Python module raises them as
/// Python warnings, which a program can catch or filter).
void warn(const std::string& message);

/// Collects the warnings of this thread while it lives (nested: the innermost collects).
class WarningCollector {
 public:
  WarningCollector();
  ~WarningCollector();
  WarningCollector(const WarningCollector&) = delete;
  WarningCollector& operator=(const WarningCollector&) = delete;
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  std::vector<std::string> messages_;
  std::vector<std::string>* outer_;
};

}  // namespace radrecon
