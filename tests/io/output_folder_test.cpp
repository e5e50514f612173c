// A run into an output folder of its own (io/output_folder.h): the earlier run's files, as its
// manifest lists them, go first; nobody else's; this run's are listed as they are written.

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

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

TEST(OutputFolderRun, KeepsAListedFileThatIsAnInputOrWasChangedSince) {
  // A manifest edited to name the scene a run reads deleted it; a report the user edited after
  // the run went too (a review).
  TempDir root("output_folder");
  const fs::path dir = root / "out";
  fs::create_directories(dir);
  write_file((dir / "scene.json").string(), "mine");
  write_file((dir / "index.html").string(), "old");
  write_file((dir / "edited.html").string(), "old");
  write_file((dir / ".m").string(), "scene.json\nindex.html\nedited.html\n.m\n");
  // edited.html changed after the manifest was written.
  fs::last_write_time(dir / "edited.html", fs::last_write_time(dir / ".m") + std::chrono::seconds(5));
  {
    OutputFolderRun run(dir, ".m", {(dir / "scene.json").string()});
    EXPECT_EQ(run.removed(), 1u);  // index.html; the manifest's naming itself is no file of the run
    EXPECT_EQ(run.kept(), 2u);
    EXPECT_NE(run.summary().find("removed the 1 file of the earlier run"), std::string::npos) << run.summary();
    EXPECT_NE(run.summary().find("kept 2 files"), std::string::npos) << run.summary();
  }
  EXPECT_TRUE(fs::exists(dir / "scene.json"));
  EXPECT_TRUE(fs::exists(dir / "edited.html"));
  EXPECT_FALSE(fs::exists(dir / "index.html"));
}

TEST(OutputFolderRun, ListsTheFilesOfManyThreadsOnceEach) {
  // paper writes from several threads: every file listed, whatever the order they came in.
  TempDir root("output_folder");
  const fs::path dir = root / "out";
  {
    OutputFolderRun run(dir, ".m");
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (int k = 0; k < 25; ++k) write_text_file(dir / ("f" + std::to_string(t) + "_" + std::to_string(k)), "x");
      });
    for (std::thread& t : threads) t.join();
    run.finish();
  }
  std::istringstream listed(read(dir / ".m"));
  std::set<std::string> names;
  for (std::string line; std::getline(listed, line);) names.insert(line);
  EXPECT_EQ(names.size(), 100u);
  EXPECT_EQ(names.count("f3_24"), 1u);
}

}  // namespace output_folder_test
}  // namespace radrecon
