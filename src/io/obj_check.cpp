#include "io/obj_check.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"

namespace radrecon {

namespace {

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
  while (std::getline(in, line))
    if (std::optional<std::string> rest = after_keyword(line, keyword)) out.push_back(std::move(*rest));
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

void check_obj_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  long long vertices = 0, line_no = 0;
  std::vector<std::pair<long long, long long>> positive;  // (index, line) checked at the end
  while (std::getline(in, line)) {
    ++line_no;
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
        // Out of range: too large (refused), or so small that it reads as 0 or a subnormal.
        if (status == NumberStatus::out_of_range && !std::isfinite(std::strtod(words[k].c_str(), nullptr)))
          throw UserError(at, "vertex coordinate " + in_quotes(words[k]) + " is out of a double's range");
        if (status == NumberStatus::not_a_number) throw UserError(at, "vertex coordinate " + in_quotes(words[k]) + " is not a number");
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
}

ObjMaterials obj_materials(const std::string& path) {
  ObjMaterials out;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const std::string& files : keyword_arguments(path, "mtllib")) {
    std::istringstream words(files);
    std::string file;
    while (words >> file) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(folder / file, ec)) {
        out.warnings.push_back(path + ": mtllib '" + file + "' not found beside it: faces of its materials are 0.5 grey, without emission");
        continue;
      }
      check_input_file_size((folder / file).string());
      // The materials defined, and colours of one value (grey), of the last `newmtl` before them.
      std::ifstream in(folder / file, std::ios::binary);
      std::string line, material;
      while (std::getline(in, line)) {
        if (std::optional<std::string> name = after_keyword(line, "newmtl")) out.defined.insert(material = std::move(*name));
        const std::vector<std::string> w = line_words(line);
        if (w.size() != 2 || (w[0] != "Kd" && w[0] != "Ke")) continue;
        double value = 0;
        if (parse_double(w[1], value) != NumberStatus::ok) continue;  // assimp's to read, and ours to refuse
        (w[0] == "Kd" ? out.grey_kd : out.grey_ke)[material] = Rgb::Constant(value);
      }
    }
  }
  return out;
}

}  // namespace radrecon
