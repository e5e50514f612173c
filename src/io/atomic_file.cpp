#include "io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <mutex>
#include <string>
#include <system_error>
#include <utility>
#include <vector>
#include <unistd.h>

#include "core/check.h"
#include "core/error.h"
#include "io/paths.h"

namespace radrecon {

namespace {

/// The temporary files and folders being written: a slot holds its path's characters while in
/// use (the handler reads them, so they are copied into storage that no thread frees).
struct PendingSlot {
  std::atomic<bool> in_use{false};
  std::atomic<bool> ready{false};
  std::atomic<bool> folder{false};  ///< a folder: what it holds is removed, then it
  char path[4096] = {};
};
PendingSlot g_pending[kMaxPendingFiles];

/// Folders within a temporary folder that the handler removes (a GDAL driver writing a folder
/// per raster, as Zarr does: two levels).
constexpr int kMaxFolderDepth = 8;

/// Empties the folder open as `fd` (closed here), its folders to `depth` more levels, with
/// async-signal-safe calls only: the entries are read by getdents64 into a buffer on the stack,
/// and read again from the start while a pass removes any (removing while reading may skip one).
void empty_folder_from_handler(int fd, int depth) {
  alignas(dirent64) char entries[4096];
  for (bool removed = true; removed;) {
    removed = false;
    if (::lseek(fd, 0, SEEK_SET) != 0) break;
    for (ssize_t n; (n = ::getdents64(fd, entries, sizeof(entries))) > 0;)
      for (ssize_t at = 0; at < n;) {
        const auto* entry = reinterpret_cast<const dirent64*>(entries + at);
        at += entry->d_reclen;
        const char* name = entry->d_name;
        if (std::strcmp(name, ".") == 0 || std::strcmp(name, "..") == 0) continue;
        if (::unlinkat(fd, name, 0) == 0) {
          removed = true;
        } else if (depth > 0) {  // a folder (EISDIR): emptied, then removed
          const int inner = ::openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (inner >= 0) empty_folder_from_handler(inner, depth - 1);
          if (::unlinkat(fd, name, AT_REMOVEDIR) == 0) removed = true;
        }
      }
  }
  ::close(fd);
}

void remove_folder_from_handler(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) empty_folder_from_handler(fd, kMaxFolderDepth);
  ::rmdir(path);
}

/// DeferredSignals alive, and the signal that came meanwhile (0: none).
std::atomic<int> g_defer_depth{0};
std::atomic<int> g_deferred_signal{0};

/// Whether a thread runs the handler: it runs once per process. sa_mask holds the other signals
/// off the thread that runs it alone, and another thread can take one meanwhile (`timeout -s HUP`
/// sends two): that one waits for the first to end the process.
std::atomic<bool> g_handling{false};
/// Whether stderr was a terminal when the handler was installed: there Ctrl-C's echoed "^C"
/// (or a progress line) ends the line, and the message starts a new one; elsewhere (a pipe, a
/// log file, --quiet under a script) it would be an empty line.
std::atomic<bool> g_stderr_terminal{false};
static_assert(std::atomic<bool>::is_always_lock_free, "lock-free: async-signal-safe");

void remove_pending_then_raise(int signal_number) {
  if (g_defer_depth.load() > 0) {
    g_deferred_signal.store(signal_number);
    if (g_defer_depth.load() > 0) return;  // raised again when the step ends
    // It ended meanwhile (and may raise it too: the second entry waits below).
  }
  if (g_handling.exchange(true))
    for (;;) ::pause();
  for (PendingSlot& slot : g_pending)
    if (slot.ready.load()) {
      if (slot.folder)
        remove_folder_from_handler(slot.path);
      else
        ::unlink(slot.path);
    }
  // Said, not only shown by the exit code (write(2) is safe in a handler; fprintf is not). A
  // closed pipe on stderr would raise SIGPIPE and end the process as that signal: ignored.
  const char* what = signal_number == SIGINT    ? "radrecon: interrupted (SIGINT); no output was left half-written under its name\n"
                     : signal_number == SIGTERM ? "radrecon: terminated (SIGTERM); no output was left half-written under its name\n"
                                                : "radrecon: hung up (SIGHUP); no output was left half-written under its name\n";
  std::signal(SIGPIPE, SIG_IGN);
  const bool own_line = signal_number != SIGINT || !g_stderr_terminal.load();
  [[maybe_unused]] const ssize_t newline = own_line ? 0 : ::write(STDERR_FILENO, "\n", 1);
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, what, std::strlen(what));
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

TemporaryPath::TemporaryPath(const std::filesystem::path& tmp, Kind kind) {
  const std::string& text = tmp.native();
  if (text.size() >= sizeof(PendingSlot::path)) return;
  for (PendingSlot& candidate : g_pending) {
    bool expected = false;
    if (candidate.in_use.compare_exchange_strong(expected, true)) {
      std::memcpy(candidate.path, text.c_str(), text.size() + 1);
      candidate.folder.store(kind == Kind::folder);
      candidate.ready.store(true);
      slot_ = &candidate;
      return;
    }
  }
}

DeferredSignals::DeferredSignals() { g_defer_depth.fetch_add(1); }

DeferredSignals::~DeferredSignals() {
  if (g_defer_depth.fetch_sub(1) == 1)
    if (const int signal_number = g_deferred_signal.exchange(0); signal_number != 0) ::raise(signal_number);
}

TemporaryPath::~TemporaryPath() {
  if (!slot_) return;
  auto* slot = static_cast<PendingSlot*>(slot_);
  slot->ready.store(false);
  slot->in_use.store(false);
}

void remove_temporary_files_on_signals() {
  g_stderr_terminal.store(::isatty(STDERR_FILENO) == 1);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    // A signal ignored on entry stays ignored, as the caller meant (nohup, a shell's trap '' or
    // its background job's SIGINT): handling it would let it end the process.
    struct sigaction inherited = {};
    if (::sigaction(signal_number, nullptr, &inherited) == 0 && !(inherited.sa_flags & SA_SIGINFO) &&
        inherited.sa_handler == SIG_IGN)
      continue;
    struct sigaction action = {};
    action.sa_handler = remove_pending_then_raise;
    // The handler returns only while DeferredSignals lives: the step's system calls go on.
    action.sa_flags = SA_RESTART;
    // One handler at a time on this thread; on other threads, g_handling holds a second off.
    sigemptyset(&action.sa_mask);
    for (const int blocked : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, blocked);
    ::sigaction(signal_number, &action, nullptr);
  }
}

namespace {

/// The live WrittenFiles' list and callback, null when none; and each file it lists, as
/// requested and as written (symbolic links followed, canonical).
std::mutex g_written_mutex;
std::vector<std::filesystem::path>* g_written = nullptr;
std::function<void(const std::filesystem::path&)> g_on_write;
std::vector<std::pair<std::filesystem::path, std::filesystem::path>> g_written_to;

/// Within a run that lists its files: refuses a write of `requested`, written at `path`, that
/// lands on a file the run wrote under another name (a link among the outputs of an existing
/// folder), before it is made. Under g_written_mutex.
void refuse_writing_twice(const std::filesystem::path& requested, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(path, ec);
  const bool linked = fs::hard_link_count(path, ec) > 1 && !ec;
  for (const auto& [name, earlier] : g_written_to)
    if (name != requested && (earlier == target || (linked && fs::equivalent(earlier, path, ec))))
      throw UserError(requested.string(), "is the same file as '" + name.string() +
                                              "', written earlier in this run; give each output its own file");
  g_written_to.emplace_back(requested, target);
}

}  // namespace

WrittenFiles::WrittenFiles(std::function<void(const std::filesystem::path&)> on_write) {
  const std::lock_guard<std::mutex> lock(g_written_mutex);
  RR_CHECK(g_written == nullptr, "one WrittenFiles at a time");
  g_written = new std::vector<std::filesystem::path>();
  g_on_write = std::move(on_write);
  g_written_to.clear();
}

WrittenFiles::~WrittenFiles() {
  const std::lock_guard<std::mutex> lock(g_written_mutex);
  delete g_written;
  g_written = nullptr;
  g_on_write = nullptr;
  g_written_to.clear();
}

std::vector<std::filesystem::path> WrittenFiles::paths() const {
  const std::lock_guard<std::mutex> lock(g_written_mutex);
  return *g_written;
}

void write_file_atomically(const std::filesystem::path& requested,
                           const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // Replace only regular files: never a folder, device or pipe; through a symlink, its target.
  const fs::path path = file_written_at(requested);
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw UserError(requested.string(), fs::is_directory(status) ? "is a folder, not a file"
                                                                  : "is not a regular file; refusing to replace it");
  {
    const std::lock_guard<std::mutex> lock(g_written_mutex);
    if (g_written != nullptr) refuse_writing_twice(requested, path);
  }
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw UserError(path.parent_path().string(), "cannot create folder: " + ec.message());
  }
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
  const TemporaryPath pending(tmp, TemporaryPath::Kind::file);  // removed by a signal until renamed or removed below
  try {
    // Replacing a file, its temporary file is made first with the file's permission bits: a
    // private output is no more readable while it is written (writers open it truncating, which
    // keeps them) than after. move_into_place() sets them again, for writers that do not.
    struct stat existing = {};
    if (::stat(path.c_str(), &existing) == 0 && S_ISREG(existing.st_mode)) {
      const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, existing.st_mode & 0777);
      if (fd >= 0) {
        [[maybe_unused]] const int set = ::fchmod(fd, existing.st_mode & 0777);  // a leftover file of another mode
        ::close(fd);
      }
    }
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  {
    // Recorded before it takes its name: an interruption between the two leaves no file of the
    // run unlisted (a listed name that is absent is nothing to remove).
    const std::lock_guard<std::mutex> lock(g_written_mutex);
    if (g_written != nullptr) {
      g_written->push_back(requested);
      if (g_on_write) g_on_write(requested);
    }
  }
  try {
    move_into_place(tmp, path);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void move_into_place(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  // The file it replaces keeps its permission bits (a private 0600 output stays private) and, for
  // root, its owner and group: best effort, a file system that keeps none is no failure.
  struct stat existing = {};
  if (::stat(path.c_str(), &existing) == 0 && S_ISREG(existing.st_mode)) {
    struct stat made = {};
    if (::geteuid() == 0 && ::stat(tmp.c_str(), &made) == 0 && (made.st_uid != existing.st_uid || made.st_gid != existing.st_gid))
      [[maybe_unused]] const int owned = ::chown(tmp.c_str(), existing.st_uid, existing.st_gid);
    ::chmod(tmp.c_str(), existing.st_mode & 0777);  // after chown, which may clear bits
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0)
    throw output_error(path.string(), errno, " (moving the finished file into place)");
}

UserError output_error(const std::string& shown_as, int error, const std::string& detail) {
  return UserError(shown_as, std::string("cannot write: ") + std::strerror(error) + detail);
}

namespace {
/// What OutputFile gathers before a write(2).
constexpr size_t kOutputBuffer = size_t{1} << 16;
}  // namespace

OutputFile::OutputFile(const std::filesystem::path& tmp, std::string shown_as) : shown_as_(std::move(shown_as)) {
  fd_ = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd_ < 0) throw output_error(shown_as_, errno, " (creating its temporary file)");
  buffer_.reserve(kOutputBuffer);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write_through(const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw output_error(shown_as_, n < 0 ? errno : EIO);
    data += n;
    size -= static_cast<size_t>(n);
  }
}

void OutputFile::flush() {
  write_through(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void OutputFile::write(const void* data, size_t size) {
  if (buffer_.size() + size > kOutputBuffer) flush();
  if (size < kOutputBuffer) buffer_.append(static_cast<const char*>(data), size);
  else write_through(static_cast<const char*>(data), size);  // large: straight from the caller's memory
}

void OutputFile::print(const char* format, ...) {
  char small[256];
  std::va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(small, sizeof(small), format, args);
  va_end(args);
  RR_CHECK(n >= 0, "an output's format is invalid");
  if (static_cast<size_t>(n) < sizeof(small)) {
    write(small, static_cast<size_t>(n));
    return;
  }
  std::string text(static_cast<size_t>(n) + 1, '\0');
  va_start(args, format);
  std::vsnprintf(text.data(), text.size(), format, args);
  va_end(args);
  text.pop_back();
  write(text);
}

void OutputFile::close() {
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && errno != EINTR) throw output_error(shown_as_, errno);
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_binary_file(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

void write_binary_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp, path.string());
    out.write(bytes.data(), bytes.size());
    out.close();  // the last bytes are written here: a full disk shows now
  });
}

}  // namespace radrecon
