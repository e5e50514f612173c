#include "io/obj_check.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"

namespace radrecon {

namespace {

/// Said of a word holding a '\' that is no number or index.
constexpr const char* kContinuation = " (a '\\' continues a statement on the next line only as the last character of a line)";

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
  ObjForAssimp out;  // its text: the file as assimp reads it, built as it is read (one copy)
  std::error_code size_error;
  const auto file_bytes = std::filesystem::file_size(path, size_error);
  if (!size_error) out.text.reserve(static_cast<size_t>(file_bytes) + 64);
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  long long lines_read = 0;
  // assimp 5.2 ends a line at a NUL, a form feed or a carriage return too, where this check
  // reads on: the statements after one would reach assimp unchecked (an "l 0" after NULs
  // crashed it, found by fuzzing). No OBJ text holds them (a line's closing CR aside). Returns
  // the line without its closing CR.
  const auto text_of = [&](const std::string& l) {
    const std::string_view body(l.data(), l.size() - (!l.empty() && l.back() == '\r' ? 1 : 0));
    if (const size_t bad = body.find_first_of(std::string_view("\0\f\r", 3)); bad != std::string_view::npos)
      throw UserError(path + ":" + std::to_string(lines_read),
                      std::string("a ") + (body[bad] == '\0' ? "NUL byte" : body[bad] == '\f' ? "form feed" : "carriage return") +
                          " within the line (byte " + std::to_string(bad + 1) + "): not OBJ text");
    return body;
  };
  while (std::getline(in, line)) {
    line_no = ++lines_read;  // a statement is named by its first line
    drop_bom(line, line_no);
    // A '\' that ends a line goes on in the next, as assimp 5.2 joins them (the '\' and the
    // line's end dropped, nothing put between): assimp is given the joined line.
    for (size_t text = text_of(line).size(); text > 0 && line[text - 1] == '\\';) {
      line.resize(text - 1);
      std::string next;
      if (!std::getline(in, next)) break;  // the file's end
      ++lines_read;
      text = line.size() + text_of(next).size();
      line += next;
    }
    // assimp's copy: its materials are radrecon's to read (obj_materials()), so no mtllib.
    // A statement that only begins with f ("foo bar"): assimp 5.2 read it as a face ("Invalid face
    // index", no line); unknown statements are skipped, as OBJ readers skip them.
    const bool unknown_f = line.size() >= 2 && line[0] == 'f' && !std::isspace(static_cast<unsigned char>(line[1]));
    if (after_keyword(line, "mtllib") || unknown_f) out.text.append("# ");
    // A vertex without its comment: assimp 5.2 counts the numbers in one among the vertex's
    // ("v 0 0 0 # 4" failed, "Cannot parse string '#'", naming no line).
    const bool vertex_line = line.size() >= 2 && line[0] == 'v' && std::isspace(static_cast<unsigned char>(line[1]));
    out.text += vertex_line ? std::string_view(line).substr(0, line.find('#')) : std::string_view(line);
    out.text += '\n';
    // A keyword of one letter, then white space or the line's end (a bare "f").
    if (line.empty() || (line.size() >= 2 && !std::isspace(static_cast<unsigned char>(line[1])))) continue;
    const std::string at = path + ":" + std::to_string(line_no);
    if (line[0] == 'v') {
      ++vertices;
      const std::vector<std::string> words = line_words(line.substr(1));
      if (words.size() < 3) throw UserError(at, "a vertex needs 3 coordinates, it has " + std::to_string(words.size()));
      // x y z, then a weight w or a colour r g b (some exporters write it; not read): assimp 5.2
      // reads a vertex of 3, 4 or 6 numbers, and divides x y z by w.
      double w = 1;
      for (size_t k = 0; k < words.size(); ++k) {
        const std::string what = k < 3 ? "vertex coordinate " : words.size() == 4 ? "vertex weight " : "vertex colour ";
        double value = 0;
        const NumberStatus status = parse_double(words[k], value);
        if (status == NumberStatus::not_finite) throw UserError(at, what + in_quotes(words[k]) + " is not finite");
        if (status == NumberStatus::out_of_range) throw UserError(at, what + in_quotes(words[k]) + " is out of a double's range");
        if (status == NumberStatus::not_a_number)
          throw UserError(at, what + in_quotes(words[k]) + " is not a number" + (words[k].find('\\') != std::string::npos ? kContinuation : ""));
        if (k == 3) w = value;
        if (k >= 3) continue;
        if (std::isinf(static_cast<float>(value)))  // beyond the largest float once rounded to one
          throw UserError(at, "vertex coordinate " + in_quotes(words[k]) +
                                  " is beyond single precision's range (3.4e38), in which the model reader holds it");
        lo[static_cast<int>(k)] = std::min(lo[static_cast<int>(k)], value), hi[static_cast<int>(k)] = std::max(hi[static_cast<int>(k)], value);
      }
      if (words.size() == 5 || words.size() > 6)
        throw UserError(at, "a vertex of " + std::to_string(words.size()) + " numbers: 'v' takes 3 coordinates x y z, with a "
                            "weight w or a colour r g b after them (3, 4 or 6 numbers)");
      if (words.size() == 4 && w != 1)
        throw UserError(at, "vertex weight w = " + format_number(w) + ": only 1 is supported (the model reader would divide x y z "
                            "by it): write x/w y/w z/w");
      continue;
    }
    if (line[0] != 'f' && line[0] != 'l' && line[0] != 'p') continue;
    const std::vector<std::string> corners = line_words(line.substr(1));
    // assimp 5.2 makes such a face a line or a point it then fails to validate, unnamed.
    if (line[0] == 'f' && corners.size() < 3)
      throw UserError(at, "a face of " + std::to_string(corners.size()) + " corner" + (corners.size() == 1 ? "" : "s") +
                              "; a face ('f') needs 3 or more (lines are 'l', points 'p', which are skipped)");
    for (const std::string& word : corners) {
      long long index = 0;
      size_t used = 0;
      try {
        index = std::stoll(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || (used < word.size() && word[used] != '/'))
        throw UserError(at, "corner " + in_quotes(word) + " is no vertex index (v, v/vt, v//vn or v/vt/vn)" +
                                (word.find('\\') != std::string::npos ? kContinuation : ""));
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
  // Far from the origin against its size (its box's centre farther than the box's diagonal):
  // moved to the origin for assimp's floats, the vertex lines rewritten (a second copy, for such
  // files only).
  if (vertices > 0 && (0.5 * (lo + hi)).norm() > (hi - lo).norm()) out.offset_m = 0.5 * (lo + hi);
  if (out.offset_m == Vec3::Zero()) return out;
  std::string moved_text;
  moved_text.reserve(out.text.size() + out.text.size() / 4);
  char number[32];
  for (size_t start = 0; start < out.text.size();) {
    const size_t end = out.text.find('\n', start);
    const std::string_view l(out.text.data() + start, end - start);
    start = end + 1;
    if (!(l.size() >= 2 && l[0] == 'v' && std::isspace(static_cast<unsigned char>(l[1])))) {
      moved_text.append(l);
      moved_text += '\n';
      continue;
    }
    const std::vector<std::string> words = line_words(std::string(l.substr(1)));
    moved_text += 'v';
    for (size_t k = 0; k < words.size(); ++k) {
      moved_text += ' ';
      if (k < 3) {  // checked above: a finite number (one that underflows reads as 0 or a subnormal)
        double value = 0;
        parse_double(words[k], value);
        const double shifted = value - out.offset_m[static_cast<int>(k)];
        const auto [last, ec] = std::to_chars(number, number + sizeof number, shifted);
        moved_text.append(number, last);
      } else {
        moved_text += words[k];
      }
    }
    moved_text += '\n';
  }
  out.text = std::move(moved_text);
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
