#pragma once
// Errors caused by user input (a malformed file, a bad option): they carry where the problem
// is (file, line, field) and end the program with exit code kUserErrorExitCode. Broken internal
// invariants are RR_CHECK failures instead (check.h); results that cannot be computed are
// returned values (std::optional), not exceptions.

#include <stdexcept>
#include <string>

namespace radrecon {

/// Exit code for every refused input, as the command-line contract fixes it.
inline constexpr int kUserErrorExitCode = 2;

class UserError : public std::runtime_error {
 public:
  /// `where` names the file and the field or line ("scene.json: surfaces[2].corners"),
  /// `what` says what is wrong with it.
  UserError(const std::string& where, const std::string& what);
  explicit UserError(const std::string& what);
};

}  // namespace radrecon
