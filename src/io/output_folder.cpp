#include "io/output_folder.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"

namespace radrecon {

namespace {

/// `path` relative to `dir`, if it lies within it (".." nowhere in the result).
std::optional<std::filesystem::path> within(const std::filesystem::path& dir, const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::weakly_canonical(dir, ec);
  if (ec) return std::nullopt;
  const std::filesystem::path full = std::filesystem::weakly_canonical(path, ec);
  if (ec) return std::nullopt;
  const std::filesystem::path rel = full.lexically_relative(base);
  if (rel.empty() || rel.is_absolute()) return std::nullopt;
  for (const std::filesystem::path& part : rel)
    if (part == "..") return std::nullopt;
  return rel;
}

}  // namespace

OutputFolderRun::OutputFolderRun(const std::filesystem::path& dir, const std::string& manifest_name,
                                 const std::vector<std::string>& inputs)
    : dir_(dir), manifest_name_(manifest_name) {
  namespace fs = std::filesystem;
  const fs::path manifest = dir / manifest_name;
  written_.emplace([this](const fs::path& p) { list(p); });
  std::error_code ec;
  if (!fs::is_regular_file(manifest, ec)) return;
  const fs::file_time_type listed_at = fs::last_write_time(manifest, ec);
  std::ifstream in(manifest);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line == manifest_name) continue;
    const std::optional<fs::path> rel = within(dir, dir / line);  // a manifest edited to reach out is not followed
    if (!rel || *rel != fs::path(line).lexically_normal()) continue;
    const fs::path file = dir / *rel;
    if (!fs::is_regular_file(fs::symlink_status(file, ec))) continue;
    // An input of this run, or a file changed after the earlier run listed it, is no longer that
    // run's output alone: kept.
    const bool input = std::any_of(inputs.begin(), inputs.end(), [&](const std::string& i) { return fs::equivalent(file, i, ec); });
    if (input || ec || fs::last_write_time(file, ec) > listed_at || ec) {
      ++kept_;
      continue;
    }
    if (!fs::remove(file, ec) && ec) throw UserError(file.string(), "cannot remove this output of an earlier run: " + ec.message());
    ++removed_;
  }
  in.close();
  if (!fs::remove(manifest, ec) && ec) throw UserError(manifest.string(), "cannot remove: " + ec.message());
}

std::string OutputFolderRun::summary() const {
  if (removed_ == 0 && kept_ == 0) return {};
  const auto files = [](size_t n) { return n == 1 ? std::string("1 file") : std::to_string(n) + " files"; };
  std::string out = "removed " + (removed_ == 1 ? std::string("the 1 file") : "the " + files(removed_)) +
                    " of the earlier run in " + dir_.string() + " (listed in its " + manifest_name_ + ")";
  if (kept_ > 0) out += "; kept " + files(kept_) + " it listed that are inputs of this run or were changed since";
  return out;
}

void OutputFolderRun::list(const std::filesystem::path& path) {
  if (!manifest_.is_open()) {
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    manifest_.open(dir_ / manifest_name_, std::ios::out | std::ios::trunc);
  }
  if (const std::optional<std::filesystem::path> rel = within(dir_, path)) manifest_ << rel->generic_string() << '\n' << std::flush;
}

void OutputFolderRun::finish() {
  std::set<std::string> files;  // sorted, once each
  for (const std::filesystem::path& p : written_->paths())
    if (const std::optional<std::filesystem::path> rel = within(dir_, p)) files.insert(rel->generic_string());
  written_.reset();  // the manifest's own writing is not listed
  manifest_.close();
  std::ostringstream text;
  for (const std::string& f : files) text << f << "\n";
  write_text_file(dir_ / manifest_name_, text.str());
}

}  // namespace radrecon
