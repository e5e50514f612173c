// A run into an output folder of its own (io/output_folder.h): the earlier run's files, as its
// manifest lists them, go first; nobody else's; this run's are listed as they are written.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/atomic_file.h"
#include "io/output_folder.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace output_folder_test {

namespace fs = std::filesystem;
using testing_support::TempDir;
using testing_support::write_file;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputFolderRun, RemovesTheEarlierRunsListedFilesAloneAndListsItsOwnAsItWritesThem) {
  TempDir root("output_folder");
  const fs::path dir = root / "out";
  fs::create_directories(dir / "figures");
  write_file((dir / "table3.md").string(), "old");
  write_file((dir / "figures/fig5_a.png").string(), "old");
  write_file((dir / "figures/fig5_my_sketch.png").string(), "mine");  // not listed: the user's
  write_file((root / "outside.txt").string(), "keep");
  // The earlier run's manifest: two of its files, one already gone, one reaching out of the folder.
  write_file((dir / ".m").string(), "table3.md\nfigures/fig5_a.png\nfigures/gone.png\n../outside.txt\n");
  {
    OutputFolderRun run(dir, ".m");
    EXPECT_EQ(run.removed(), 2u);
    EXPECT_FALSE(fs::exists(dir / "table3.md"));
    EXPECT_FALSE(fs::exists(dir / "figures/fig5_a.png"));
    EXPECT_TRUE(fs::exists(dir / "figures/fig5_my_sketch.png"));
    EXPECT_TRUE(fs::exists(root / "outside.txt"));
    write_text_file(dir / "table1.md", "new");
    write_text_file(root / "elsewhere.txt", "not the folder's");
    // Listed as written, before finish(): an interrupted run's files are the next run's to remove.
    EXPECT_EQ(read(dir / ".m"), "table1.md\n");
    write_text_file(dir / "figures/fig3_b.png", "new");
    run.finish();
  }
  EXPECT_EQ(read(dir / ".m"), "figures/fig3_b.png\ntable1.md\n");  // sorted, rewritten whole
  // The next run removes exactly those.
  OutputFolderRun next(dir, ".m");
  EXPECT_EQ(next.removed(), 2u);
  EXPECT_FALSE(fs::exists(dir / "table1.md"));
  EXPECT_TRUE(fs::exists(dir / "figures/fig5_my_sketch.png"));
  EXPECT_TRUE(fs::exists(root / "elsewhere.txt"));
}

}  // namespace output_folder_test
}  // namespace radrecon
