#pragma once
// Output files appear whole or not at all: content goes to a temporary file beside the target,
// which is renamed over it only once complete.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace radrecon {

/// Calls write(tmp_path) to produce the file, then renames tmp_path to `path`. On any exception
/// the temporary file is removed and the exception propagates; `path` is left untouched.
/// Creates the parent folders of `path`. A failed rename throws output_error().
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// While one lives, every file write_file_atomically() completes (from any thread) is recorded:
/// the files a run writes (io/output_folder.h). A write that would land on a file recorded under
/// another name (a symbolic or hard link among the outputs in an existing folder) is refused
/// before it is made, naming both. At most one at a time.
class WrittenFiles {
 public:
  /// `on_write`, if given, is called with each path as it is recorded (under a lock: one call at a
  /// time).
  explicit WrittenFiles(std::function<void(const std::filesystem::path&)> on_write = {});
  ~WrittenFiles();
  WrittenFiles(const WrittenFiles&) = delete;
  WrittenFiles& operator=(const WrittenFiles&) = delete;
  /// The paths written so far, as requested (not through their symbolic links), in order.
  std::vector<std::filesystem::path> paths() const;
};

/// From the call on, SIGINT, SIGTERM and SIGHUP first remove the temporary files that
/// write_file_atomically() has open and the folders that live TemporaryPath objects name (at most
/// kMaxPendingFiles at a time), then end the process as the signal would have: an interrupted
/// long write (a streamed raster, a render, a GDAL raster's folder) leaves no `.tmpPID` file or
/// `.radrecon-gdal-XXXXXX` folder behind. For programs that own their signals (radrecon's command
/// line), not for a library loaded into another (the Python module). A signal ignored when this
/// is called (nohup's SIGHUP, a shell's `trap ''`) is left ignored.
void remove_temporary_files_on_signals();

/// Temporary files and folders tracked for the signal handler at once; more are written as
/// usual, untracked.
inline constexpr int kMaxPendingFiles = 16;

/// While alive, names a temporary file or folder for the signal handler of
/// remove_temporary_files_on_signals() to remove (a folder with everything in it, to 8 levels of
/// folders; nothing if all kMaxPendingFiles slots are taken or the path is over 4,095 bytes). It
/// removes nothing itself.
class TemporaryPath {
 public:
  enum class Kind { file, folder };
  TemporaryPath(const std::filesystem::path& tmp, Kind kind);
  ~TemporaryPath();
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;

 private:
  void* slot_ = nullptr;  ///< the handler's slot, opaque here
};

/// While one lives, SIGINT, SIGTERM and SIGHUP wait: the handler of
/// remove_temporary_files_on_signals() notes the signal and returns, and the last one to end
/// raises it, which then cleans up and ends the process as usual. For a step that must not stop
/// half-way: moving a GDAL raster's files into place one by one.
class DeferredSignals {
 public:
  DeferredSignals();
  ~DeferredSignals();
  DeferredSignals(const DeferredSignals&) = delete;
  DeferredSignals& operator=(const DeferredSignals&) = delete;
};

/// Renames the finished file `tmp` to `path` (the name itself: a symbolic link there is replaced,
/// not followed); output_error() naming `path` if the system refuses, `tmp` left to the caller.
/// An existing file at `path` passes its permission bits to `tmp` first (and, when running as
/// root, its owner and group), best effort: replacing an output keeps its mode.
void move_into_place(const std::filesystem::path& tmp, const std::filesystem::path& path);

/// The one wording of an output that cannot be written: UserError naming `shown_as` (the output as
/// the user named it, not its temporary file), "cannot write: " and the system's reason for
/// `error`, an errno value taken right after the failing call ("No space left on device"), then
/// `detail` (" (...)" or "").
UserError output_error(const std::string& shown_as, int error, const std::string& detail = "");

/// An output file written by write_file_atomically()'s callback: buffered writes straight to the
/// file, every failure (a full disk, a file-size limit, a failing close) an output_error() naming
/// `shown_as`, with the reason of the call that failed.
class OutputFile {
 public:
  /// Creates or truncates `tmp`.
  OutputFile(const std::filesystem::path& tmp, std::string shown_as);
  ~OutputFile();  ///< closes the file unchecked if close() was not reached (an exception)
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  void write(const void* data, size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Appends printf's formatting of the arguments.
  void print(const char* format, ...) __attribute__((format(printf, 2, 3)));
  /// Writes what is buffered and closes the file: the last bytes' failure shows here at the latest.
  void close();

 private:
  void write_through(const char* data, size_t size);
  void flush();
  int fd_ = -1;
  std::string shown_as_;
  std::string buffer_;
};

/// Writes `text` to `path` atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);

/// Writes `bytes` to `path` atomically; a failed write, the final flush's included (a full
/// disk), throws output_error() naming `path`.
void write_binary_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);

}  // namespace radrecon
