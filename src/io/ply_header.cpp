#include "io/ply_header.h"

#include <cstdint>
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
  std::string format;
  std::vector<Element> elements;
  for (std::string line = next_line(); line != "end_header"; line = next_line()) {
    std::istringstream in(line);
    std::string word;
    in >> word;
    const std::string where = "PLY header line " + std::to_string(line_no) + ": ";
    if (word == "format") {
      in >> format;
    } else if (word == "element") {
      Element e;
      long long count = -1;
      if (!(in >> e.name >> count) || count < 0) throw bad(where + "malformed element line");
      e.count = static_cast<size_t>(count);
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) throw bad(where + "property before any element");
      std::string type;
      in >> type;
      Property p;
      if (type == "list") {
        std::string count_type, item_type;
        in >> count_type >> item_type;
        p.count_size = type_size(count_type);
        p.size = type_size(item_type);
        if (p.count_size == 0 || p.size == 0) throw bad(where + "unknown list types '" + count_type + " " + item_type + "'");
      } else {
        p.size = type_size(type);
        if (p.size == 0) throw bad(where + "unknown property type '" + type + "'");
      }
      elements.back().properties.push_back(p);
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw bad(where + "unknown keyword '" + word + "'");
    }
  }
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
