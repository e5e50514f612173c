#pragma once
// Output files appear whole or not at all: content goes to a temporary file beside the target,
// which is renamed over it only once complete.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>

namespace radrecon {

/// Calls write(tmp_path) to produce the file, then renames tmp_path to `path`. On any exception
/// the temporary file is removed and the exception propagates; `path` is left untouched.
/// Creates the parent folders of `path`.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` to `path` atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// Writes `bytes` to `path` atomically; a failed write, the final flush's included (a full
/// disk), throws UserError naming `path`.
void write_binary_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace radrecon
