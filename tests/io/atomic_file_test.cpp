// Output files written whole or not at all (io/atomic_file.h): a write that fails says why, in
// the system's words, and leaves neither the file nor its temporary file.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>

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

TEST(WriteBinaryFile, WritesTheBytes) {
  TempDir root("atomic_file");
  const fs::path target = root / "a.bin";
  const std::uint8_t bytes[] = {1, 2, 3, 0, 255};
  write_binary_file(target, bytes);
  EXPECT_EQ(fs::file_size(target), 5u);
}

}  // namespace atomic_file_test
}  // namespace radrecon
