#pragma once

#include <gtest/gtest.h>
// Test helpers for files: a scratch folder that cleans up after itself, and the message of a
// refusal.

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace radrecon::testing_support {

/// A fresh folder under the system's temporary folder, removed with its contents when the
/// object goes out of scope.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// The message of the UserError that f throws, or "" if it throws none.
template <typename F>
std::string user_error_message(F f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

/// Passes when f throws a UserError whose message holds every one of `needles`; fails naming what
/// happened instead (accepted, another exception, a needle missing).
template <typename F>
testing::AssertionResult refused_mentioning(F f, const std::vector<std::string>& needles) {
  try {
    f();
  } catch (const UserError& e) {
    const std::string message = e.what();
    for (const std::string& needle : needles)
      if (message.find(needle) == std::string::npos)
        return testing::AssertionFailure() << "message \"" << message << "\" does not mention \"" << needle << "\"";
    return testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return testing::AssertionFailure() << "threw a non-UserError exception: " << e.what();
  } catch (...) {
    return testing::AssertionFailure() << "threw something that is not a std::exception";
  }
  return testing::AssertionFailure() << "accepted";
}

}  // namespace radrecon::testing_support
