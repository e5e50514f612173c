#include "io/ply_header.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

/// Bytes of a PLY scalar type; 0 if unknown.
size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

struct Property {
  size_t size = 0;        ///< scalar: its bytes; list: the bytes of an item
  size_t count_size = 0;  ///< list: the bytes of its count; 0 for a scalar
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
};

}  // namespace

size_t check_ply_size(const std::string& path) {
  const std::string bytes = read_text_file(path, "mesh file");
  const auto bad = [&](const std::string& what) { return UserError(path, what); };
  size_t pos = 0, line_no = 0;
  const auto next_line = [&]() {
    const size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) throw bad("PLY header has no end_header line");
    std::string line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    ++line_no;
    return line;
  };
  if (next_line() != "ply") throw bad("not a PLY file (its first line is not 'ply')");
  // The header is read as strictly as the format's definition says: assimp's reader takes
  // liberties with malformed headers (a second format line, counts like '1.0', trailing words)
  // that it should refuse, and the fuzzers found its heap corrupted after such inputs.
  std::string format;
  std::vector<Element> elements;
  const auto words_of = [](const std::string& line) {
    std::vector<std::string> words;
    std::istringstream in(line);
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  };
  // Element names are identifiers: assimp reads an element named '111...vertex' as a count of
  // 10^44 vertices and allocates for them.
  // (Property names are any word: custom attributes use '-', '.' and ':'.)
  const auto is_name = [](const std::string& word) {
    return !word.empty() && (std::isalpha(static_cast<unsigned char>(word[0])) || word[0] == '_') &&
           std::all_of(word.begin(), word.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  };
  const auto count_of = [](const std::string& word) -> std::optional<size_t> {
    if (word.empty() || word.size() > 18 || word.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    return static_cast<size_t>(std::stoull(word));
  };
  for (std::string line = next_line(); line != "end_header"; line = next_line()) {
    const std::vector<std::string> words = words_of(line);
    const std::string where = "PLY header line " + std::to_string(line_no) + ": ";
    const std::string word = words.empty() ? "" : words[0];
    if (word == "format") {
      if (line_no != 2) throw bad(where + "the format line must be the second line");
      if (words.size() != 3 || words[2] != "1.0") throw bad(where + "malformed format line (expected 'format TYPE 1.0')");
      format = words[1];
    } else if (word == "element") {
      const std::optional<size_t> count = words.size() == 3 ? count_of(words[2]) : std::nullopt;
      if (!count || !is_name(words[1])) throw bad(where + "malformed element line (expected 'element NAME COUNT')");
      for (const Element& e : elements)
        if (e.name == words[1]) throw bad(where + "element '" + words[1] + "' declared twice");
      elements.push_back({words[1], *count, {}});
    } else if (word == "property") {
      if (elements.empty()) throw bad(where + "property before any element");
      Property p;
      if (words.size() >= 2 && words[1] == "list") {
        if (words.size() != 5) throw bad(where + "malformed property line (expected 'property list COUNT_TYPE ITEM_TYPE NAME')");
        p.count_size = type_size(words[2]);
        p.size = type_size(words[3]);
        if (p.count_size == 0 || p.size == 0) throw bad(where + "unknown list types '" + words[2] + " " + words[3] + "'");
      } else {
        if (words.size() != 3) throw bad(where + "malformed property line (expected 'property TYPE NAME')");
        p.size = type_size(words[1]);
        if (p.size == 0) throw bad(where + "unknown property type '" + words[1] + "'");
      }
      elements.back().properties.push_back(p);
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw bad(where + "unknown keyword '" + word + "'");
    }
  }
  if (format.empty()) throw bad("PLY header has no format line");
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    throw bad("PLY header: unknown format '" + format + "'");
  size_t faces = 0;
  for (const Element& e : elements)
    if (e.name == "face") faces += e.count;
  const auto truncated = [&](const Element& e, size_t record) {
    return bad("truncated: the data ends in " + e.name + " " + std::to_string(record) + " of the " +
               std::to_string(e.count) + " its header declares");
  };
  if (format == "ascii") {
    std::istringstream in(bytes.substr(pos));
    std::string token;
    for (const Element& e : elements)
      for (size_t r = 0; r < e.count; ++r)
        for (const Property& p : e.properties) {
          if (!(in >> token)) throw truncated(e, r);
          if (p.count_size == 0) continue;
          long long n = -1;
          try {
            n = std::stoll(token);
          } catch (const std::exception&) {
          }
          if (n < 0) throw bad("malformed: " + e.name + " " + std::to_string(r) + " has a list count '" + token + "'");
          for (long long k = 0; k < n; ++k)
            if (!(in >> token)) throw truncated(e, r);
        }
    return faces;
  }
  const bool big = format == "binary_big_endian";
  for (const Element& e : elements)
    for (size_t r = 0; r < e.count; ++r)
      for (const Property& p : e.properties) {
        if (p.count_size == 0) {
          if (bytes.size() - pos < p.size) throw truncated(e, r);
          pos += p.size;
          continue;
        }
        if (bytes.size() - pos < p.count_size) throw truncated(e, r);
        uint64_t n = 0;
        for (size_t k = 0; k < p.count_size; ++k) {
          const size_t at = big ? k : p.count_size - 1 - k;
          n = (n << 8) | static_cast<unsigned char>(bytes[pos + at]);
        }
        pos += p.count_size;
        if (n > (bytes.size() - pos) / p.size) throw truncated(e, r);
        pos += n * p.size;
      }
  return faces;
}

}  // namespace radrecon
