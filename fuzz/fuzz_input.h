#pragma once
// What every libFuzzer harness of radrecon shares (docs/hostile.md, "Fuzzing"): the input written to a file
// of a given extension (the readers take paths, as the command line gives them), and the rule
// that a reader may refuse an input only with a UserError. Any other exception escapes the
// harness, and libFuzzer reports it as a crash: a message without the file and the field is a
// defect too.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace radrecon::fuzz {

/// The process's folder for its input files: radrecon-fuzz-PID in $RADRECON_FUZZ_TMP (set by
/// fuzz/run.sh and ctest to folders they own), else in /dev/shm or /tmp. libFuzzer ends with
/// _Exit, so a process cannot remove its own folder: whoever sets the variable does.
inline const std::filesystem::path& input_folder() {
  static const std::filesystem::path folder = [] {
    const char* set = std::getenv("RADRECON_FUZZ_TMP");
    const std::filesystem::path base = set != nullptr && *set != '\0'                     ? set
                                       : std::filesystem::is_directory("/dev/shm") ? "/dev/shm"
                                                                                   : "/tmp";
    std::filesystem::path f = base / ("radrecon-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(f);
    return f;
  }();
  return folder;
}

/// Writes the input to one file per process and extension, in /dev/shm when there is one, and
/// returns its path. The file is overwritten by the next input.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::filesystem::path& folder = input_folder();
  const std::string path = (folder / ("input" + extension)).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

/// Runs `read` and accepts a UserError as the reader's refusal.
template <typename F>
void expect_success_or_refusal(F&& read) {
  try {
    read();
  } catch (const UserError&) {
  }
}

}  // namespace radrecon::fuzz
