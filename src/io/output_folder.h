#pragma once
// A command's run into an output folder of its own (radrecon paper, radrecon cornell): what an
// earlier run wrote there goes before this run writes anything, so nothing of it stands beside
// the new results as if it were of them, and an interrupted run leaves its own files, not a mix
// of two runs; files of anyone else stay. The folder's manifest, a file named by the command,
// lists the files of the run that wrote it, relative to the folder, one a line.

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.h"

namespace radrecon {

class OutputFolderRun {
 public:
  /// Removes the files the folder's manifest `manifest_name` lists (those that exist, only within
  /// the folder), but not one of `inputs` (the run's own) nor one changed since the manifest was
  /// written (someone else's now), then lists in the manifest every file this run writes within
  /// the folder through write_file_atomically(), as it is written (so an interrupted run's are
  /// removed by the next). To be made once the run's input is checked, before its first write:
  /// a refused run leaves the earlier results alone. UserError naming a file that cannot be
  /// removed.
  OutputFolderRun(const std::filesystem::path& dir, const std::string& manifest_name,
                  const std::vector<std::string>& inputs = {});
  /// How many files of an earlier run the constructor removed, and how many it kept (inputs,
  /// files changed since).
  size_t removed() const { return removed_; }
  size_t kept() const { return kept_; }
  /// What the constructor did, for the command's stderr ("" when it removed and kept nothing):
  /// "removed the 3 files of the earlier run in DIR (listed in its MANIFEST)".
  std::string summary() const;
  /// Rewrites the manifest whole, sorted: the files written since the constructor within the
  /// folder.
  void finish();

 private:
  /// Appends `path` to the manifest if it lies within the folder (WrittenFiles' callback).
  void list(const std::filesystem::path& path);

  std::filesystem::path dir_;
  std::string manifest_name_;
  size_t removed_ = 0, kept_ = 0;
  std::ofstream manifest_;  ///< appended to as files are written
  std::optional<WrittenFiles> written_;
};

}  // namespace radrecon
