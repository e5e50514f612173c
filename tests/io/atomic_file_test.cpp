// Output files written whole or not at all (io/atomic_file.h): a write that fails says why, in
// the system's words, and leaves neither the file nor its temporary file.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "core/error.h"
#include "io/atomic_file.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace atomic_file_test {

namespace fs = std::filesystem;
using testing_support::TempDir;
using testing_support::user_error_message;

TEST(OutputFile, AFullDiskIsSaidWithTheSystemsReasonNamingTheOutput) {
  // /dev/full takes the bytes and fails each write with ENOSPC.
  const std::string said = user_error_message([] {
    OutputFile out("/dev/full", "sol.json");
    out.write("{}\n");
    out.close();
  });
  EXPECT_EQ(said, "sol.json: cannot write: No space left on device");
}

TEST(OutputFile, ALargeWriteFailsAtOnce) {
  const std::string big(1 << 20, 'x');  // beyond the buffer: written straight through
  const std::string said = user_error_message([&] {
    OutputFile out("/dev/full", "big.csv");
    out.write(big);
  });
  EXPECT_EQ(said, "big.csv: cannot write: No space left on device");
}

TEST(WriteFileAtomically, AFailedRenameSaysTheRenamesReasonAndLeavesNoTemporaryFile) {
  TempDir root("atomic_file");
  const fs::path target = root / "out.json";
  // Made a folder, with a file in it, while the output is written: the rename onto it fails.
  const std::string said = user_error_message([&] {
    write_file_atomically(target, [&](const fs::path& tmp) {
      testing_support::write_file(tmp.string(), "{}\n");
      fs::create_directory(target);
      testing_support::write_file((target / "x").string(), "x");
    });
  });
  EXPECT_NE(said.find(target.string() + ": cannot write: Is a directory"), std::string::npos) << said;
  EXPECT_EQ(said.find("Success"), std::string::npos) << said;
  size_t entries = 0;
  for ([[maybe_unused]] const fs::directory_entry& e : fs::directory_iterator(root.path())) ++entries;
  EXPECT_EQ(entries, 1u) << "the temporary file is left";
}

// In a run that lists its files (paper, cornell), a write that would land on a file the run wrote
// under another name, through a link planted among its outputs, is refused before it is made; the
// same name twice is a rewrite.
TEST(WrittenFiles, AWriteOntoAnotherOutputOfTheRunIsRefused) {
  TempDir root("atomic_file");
  fs::create_symlink("b.png", root / "a.png");
  const WrittenFiles run;
  write_text_file(root / "b.png", "b");
  write_text_file(root / "b.png", "b again");
  const std::string said = user_error_message([&] { write_text_file(root / "a.png", "a"); });
  EXPECT_EQ(said, (root / "a.png").string() + ": is the same file as '" + (root / "b.png").string() +
                      "', written earlier in this run; give each output its own file");
  EXPECT_EQ(run.paths().size(), 2u);
  std::ifstream in(root / "b.png");
  std::string kept;
  std::getline(in, kept);
  EXPECT_EQ(kept, "b again");
}

TEST(WriteBinaryFile, WritesTheBytes) {
  TempDir root("atomic_file");
  const fs::path target = root / "a.bin";
  const std::uint8_t bytes[] = {1, 2, 3, 0, 255};
  write_binary_file(target, bytes);
  EXPECT_EQ(fs::file_size(target), 5u);
}

/// How many threads of process `pid` are in the system call `number` (/proc/PID/task/*/syscall).
int threads_in_syscall(pid_t pid, long number) {
  int count = 0;
  for (const fs::directory_entry& task : fs::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream in(task.path() / "syscall");
    long got = -1;
    if (in >> got && got == number) ++count;
  }
  return count;
}

// Two threads taking a signal each, as `timeout -s HUP` may make them: the handler runs once, one
// message (it was said twice). A child process, its stderr a pipe filled up first, so that a
// handler's message waits in write(2) until the parent reads: after both signals, one thread is
// in write(2) (it was both), and the process ends by the signal with one message.
TEST(RemoveTemporaryFilesOnSignals, RunsOnceWhenTwoThreadsTakeASignal) {
  int err[2];
  ASSERT_EQ(::pipe(err), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::dup2(err[1], STDERR_FILENO);
    ::close(err[0]);
    ::close(err[1]);
    ::fcntl(STDERR_FILENO, F_SETFL, O_NONBLOCK);
    const char fill[512] = {};
    while (::write(STDERR_FILENO, fill, sizeof fill) > 0) {}
    ::fcntl(STDERR_FILENO, F_SETFL, 0);
    remove_temporary_files_on_signals();
    std::thread second([] {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      std::raise(SIGHUP);  // this thread's, while the main thread's handler waits to write
    });
    std::raise(SIGHUP);
    ::_exit(3);  // not reached
  }
  ::close(err[1]);
  int writing = 0;
  for (int tries = 0; tries < 50 && writing < 2; ++tries) {  // long enough for both signals
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (tries >= 25) writing = threads_in_syscall(child, SYS_write);
  }
  EXPECT_EQ(writing, 1) << "threads running the handler at once";
  std::string said;
  char buffer[4096];
  for (ssize_t n; (n = ::read(err[0], buffer, sizeof buffer)) > 0;) said.append(buffer, static_cast<size_t>(n));
  ::close(err[0]);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGHUP) << status;
  size_t messages = 0;
  for (size_t at = 0; (at = said.find("radrecon: hung up (SIGHUP)", at)) != std::string::npos; ++at) ++messages;
  EXPECT_EQ(messages, 1u);
}

// Replacing a private (0600) output: its temporary file is 0600 while it is written, not the
// umask's 0644 until the rename (another user could read a long write), and so is the result.
TEST(WriteFileAtomically, APrivateOutputStaysPrivateWhileItIsWritten) {
  const TempDir dir("radrecon_private_output");
  const fs::path out = dir.path() / "private.json";
  std::ofstream(out) << "old";
  fs::permissions(out, fs::perms::owner_read | fs::perms::owner_write);
  fs::perms while_written = fs::perms::none;
  write_file_atomically(out, [&](const fs::path& tmp) {
    std::ofstream(tmp) << "new";
    while_written = fs::status(tmp).permissions();
  });
  EXPECT_EQ(while_written, fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(fs::status(out).permissions(), fs::perms::owner_read | fs::perms::owner_write);
  std::string content;
  std::ifstream(out) >> content;
  EXPECT_EQ(content, "new");
}

/// Runs `body` in a child process with the handlers installed and its stderr to /dev/null; returns
/// the child's wait status.
template <class Body>
int in_child(Body body) {
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDERR_FILENO);
    remove_temporary_files_on_signals();
    body();
    ::_exit(3);  // not reached when the body raises a signal
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

// A temporary folder holding folders (GDAL's Zarr driver writes one per raster, with folders in
// it) is removed whole by the handler; a folder beside it is not touched.
TEST(RemoveTemporaryFilesOnSignals, RemovesATemporaryFolderWithFoldersInIt) {
  const TempDir dir("radrecon_signal_folder");
  const fs::path staging = dir.path() / ".radrecon-gdal-test";
  fs::create_directories(staging / "big.zarr" / "0" / "1");
  std::ofstream(staging / "big.zarr" / ".zarray") << "{}";
  std::ofstream(staging / "big.zarr" / "0" / "1" / "0") << "chunk";
  std::ofstream(staging / "big.aux.xml") << "<x/>";
  fs::create_directories(dir.path() / "kept");
  std::ofstream(dir.path() / "kept" / "file") << "mine";
  const int status = in_child([&] {
    const TemporaryPath pending(staging, TemporaryPath::Kind::folder);
    std::raise(SIGTERM);
  });
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_TRUE(fs::exists(dir.path() / "kept" / "file"));
}

// A signal while DeferredSignals lives waits for it to end: the step goes on (here, writes a file),
// then the process ends by that signal, the temporary file removed.
TEST(DeferredSignals, ASignalWaitsForTheStepThenEndsTheProcess) {
  const TempDir dir("radrecon_signal_deferred");
  const fs::path tmp = dir.path() / "out.tmp1", done = dir.path() / "step_done";
  std::ofstream(tmp) << "partial";
  const int status = in_child([&] {
    const TemporaryPath pending(tmp, TemporaryPath::Kind::file);
    {
      const DeferredSignals step;
      std::raise(SIGINT);
      std::ofstream(done) << "the step went on";
    }
    ::_exit(4);  // not reached: the deferred signal ends the process
  });
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_TRUE(fs::exists(done));
  EXPECT_FALSE(fs::exists(tmp));
}

}  // namespace atomic_file_test
}  // namespace radrecon
