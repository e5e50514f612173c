#include "io/obj_check.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"

namespace radrecon {

namespace {

/// A UTF-8 byte-order mark, which some editors write at the start of a text file.
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

/// The line with a byte-order mark dropped if it is the file's first.
void drop_bom(std::string& line, long long line_no) {
  if (line_no == 1 && line.starts_with(kUtf8Bom)) line.erase(0, kUtf8Bom.size());
}

/// What follows `keyword` on a line that starts with it (blanks at either end dropped).
std::optional<std::string> after_keyword(const std::string& line, const std::string& keyword) {
  const size_t start = line.find_first_not_of(" \t");
  if (start == std::string::npos || line.compare(start, keyword.size(), keyword) != 0) return std::nullopt;
  const size_t after = start + keyword.size();
  if (after >= line.size() || !std::isspace(static_cast<unsigned char>(line[after]))) return std::nullopt;
  return std::string(trim_blanks(std::string_view(line).substr(after)));
}

/// The words after `keyword` on each line of the file that starts with it.
std::vector<std::string> keyword_arguments(const std::filesystem::path& file, const std::string& keyword) {
  std::vector<std::string> out;
  std::ifstream in(file, std::ios::binary);
  std::string line;
  for (long long line_no = 1; std::getline(in, line); ++line_no) {
    drop_bom(line, line_no);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (std::optional<std::string> rest = after_keyword(line, keyword)) out.push_back(std::move(*rest));
  }
  return out;
}

/// The words of a line of an OBJ or MTL file, up to a '#' comment.
std::vector<std::string> line_words(const std::string& line) {
  std::istringstream in(line.substr(0, line.find('#')));
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(std::move(word));
  return out;
}

}  // namespace

ObjForAssimp check_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long long vertices = 0, line_no = 0;
  std::vector<std::pair<long long, long long>> positive;  // (index, line) checked at the end
  std::vector<std::string> lines;  // the file, for assimp's copy
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  while (std::getline(in, line)) {
    ++line_no;
    drop_bom(line, line_no);
    lines.push_back(line);
    if (line.size() < 2 || !std::isspace(static_cast<unsigned char>(line[1]))) continue;
    const std::string at = path + ":" + std::to_string(line_no);
    if (line[0] == 'v') {
      ++vertices;
      const std::vector<std::string> words = line_words(line.substr(1));
      if (words.size() < 3) throw UserError(at, "a vertex needs 3 coordinates, it has " + std::to_string(words.size()));
      for (size_t k = 0; k < 3; ++k) {
        double value = 0;
        const NumberStatus status = parse_double(words[k], value);
        if (status == NumberStatus::not_finite) throw UserError(at, "vertex coordinate " + in_quotes(words[k]) + " is not finite");
        if (status == NumberStatus::out_of_range)
          throw UserError(at, "vertex coordinate " + in_quotes(words[k]) + " is out of a double's range");
        if (status == NumberStatus::not_a_number) throw UserError(at, "vertex coordinate " + in_quotes(words[k]) + " is not a number");
        lo[static_cast<int>(k)] = std::min(lo[static_cast<int>(k)], value), hi[static_cast<int>(k)] = std::max(hi[static_cast<int>(k)], value);
      }
      continue;
    }
    if (line[0] != 'f' && line[0] != 'l' && line[0] != 'p') continue;
    const std::vector<std::string> corners = line_words(line.substr(1));
    // assimp 5.2 makes such a face a line or a point it then fails to validate, unnamed. (A line
    // ending in '\\' goes on in the next, as assimp reads it: its corners are not all here.)
    const bool continued = !corners.empty() && corners.back().ends_with('\\');
    if (line[0] == 'f' && corners.size() < 3 && !continued)
      throw UserError(at, "a face of " + std::to_string(corners.size()) + " corner" + (corners.size() == 1 ? "" : "s") +
                              "; a face ('f') needs 3 or more (lines are 'l', points 'p', which are skipped)");
    for (const std::string& word : corners) {
      long long index = 0;
      try {
        size_t used = 0;
        index = std::stoll(word, &used);
        if (used < word.size() && word[used] != '/') continue;
      } catch (const std::exception&) {
        continue;  // not a number: assimp's to refuse
      }
      const long long absolute = index < 0 ? vertices + 1 + index : index;
      if (index == 0 || absolute < 1)
        throw UserError(at, "vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertices) + " vertices before it)");
      if (index > 0) positive.push_back({index, line_no});
    }
  }
  for (const auto& [index, at] : positive)
    if (index > vertices)
      throw UserError(path + ":" + std::to_string(at),
                      "vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertices) + " vertices)");
  ObjForAssimp out;
  // Far from the origin against its size (its box's centre farther than the box's diagonal):
  // moved to the origin for assimp's floats.
  if (vertices > 0 && (0.5 * (lo + hi)).norm() > (hi - lo).norm()) out.offset_m = 0.5 * (lo + hi);
  size_t bytes = 0;
  for (const std::string& l : lines) bytes += l.size() + 1;
  out.text.reserve(bytes);
  char number[32];
  for (std::string& l : lines) {
    if (after_keyword(l, "mtllib")) {
      l.insert(l.find_first_not_of(" \t"), "# ");
    } else if (out.offset_m != Vec3::Zero() && l.size() >= 2 && l[0] == 'v' && std::isspace(static_cast<unsigned char>(l[1]))) {
      const std::string comment = l.find('#') == std::string::npos ? "" : l.substr(l.find('#'));
      const std::vector<std::string> words = line_words(l.substr(1));
      std::string moved = "v";
      for (size_t k = 0; k < words.size(); ++k) {
        moved += ' ';
        double value = 0;
        if (k < 3) {  // checked above: a finite number (one that underflows reads as 0 or a subnormal)
          parse_double(words[k], value);
          const double shifted = value - out.offset_m[static_cast<int>(k)];
          const auto [end, ec] = std::to_chars(number, number + sizeof number, shifted);
          moved.append(number, end);
        } else {
          moved += words[k];
        }
      }
      l = moved + (comment.empty() ? "" : " " + comment);
    }
    out.text += l;
    out.text += '\n';
  }
  return out;
}

namespace {

/// A Kd or Ke statement's colour: one number (grey) or three, each finite; refused naming the
/// MTL file and line.
Rgb mtl_colour(const std::vector<std::string>& words, const std::string& at, const std::string& obj) {
  const std::string& key = words[0];
  if (words.size() != 2 && words.size() != 4)
    throw UserError(at, key + " must be one number (grey) or three (r g b), got " + std::to_string(words.size() - 1) +
                            " value(s)" + (words.size() > 1 && (words[1] == "spectral" || words[1] == "xyz")
                                              ? " (" + words[1] + " colours are not read: give r g b)" : "") +
                            " (an MTL file of " + obj + ")");
  Rgb c;
  for (int k = 0; k < 3; ++k) {
    const std::string& word = words[words.size() == 2 ? 1 : static_cast<size_t>(k) + 1];
    double value = 0;
    if (parse_double(word, value) != NumberStatus::ok)
      throw UserError(at, key + " value " + in_quotes(word) + " is not a finite number (an MTL file of " + obj + ")");
    c[k] = value;
  }
  return c;
}

}  // namespace

ObjMaterials obj_materials(const std::string& path) {
  ObjMaterials out;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const std::string& files : keyword_arguments(path, "mtllib")) {
    // One file named by the whole line (with spaces, as Blender writes it) if there is one, else
    // a file a word.
    std::vector<std::string> names;
    std::error_code ec;
    if (files.find_first_of(" \t") != std::string::npos && std::filesystem::is_regular_file(folder / files, ec)) {
      names.push_back(files);
    } else {
      std::istringstream words(files);
      for (std::string file; words >> file;) names.push_back(file);
    }
    for (const std::string& file : names) {
      if (!std::filesystem::is_regular_file(folder / file, ec)) {
        out.warnings.push_back(path + ": mtllib '" + file + "' not found beside it: faces of its materials are 0.5 grey, without emission");
        continue;
      }
      const std::string mtl = (folder / file).string();
      check_input_file_size(mtl);
      std::ifstream in(folder / file, std::ios::binary);
      std::string line;
      ObjMaterial* material = nullptr;  // the last `newmtl`'s
      for (long long line_no = 1; std::getline(in, line); ++line_no) {
        drop_bom(line, line_no);
        if (std::optional<std::string> name = after_keyword(line, "newmtl")) {
          material = &out.defined[*name];
          *material = ObjMaterial{};  // a name defined again: its last definition
          continue;
        }
        const std::vector<std::string> w = line_words(line);
        if (w.empty() || (w[0] != "Kd" && w[0] != "Ke")) continue;
        const Rgb colour = mtl_colour(w, mtl + ":" + std::to_string(line_no), path);
        if (material == nullptr) continue;  // before any newmtl: of no material
        (w[0] == "Kd" ? material->kd : material->ke) = colour;
      }
    }
  }
  return out;
}

}  // namespace radrecon
