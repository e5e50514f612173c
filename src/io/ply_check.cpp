#include "io/ply_check.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

/// A PLY scalar type: its bytes in a binary file and its kind.
struct ScalarType {
  size_t bytes = 0;
  bool is_signed = false;
  bool is_real = false;
};

std::optional<ScalarType> scalar_type(const std::string& t) {
  if (t == "char" || t == "int8") return ScalarType{1, true, false};
  if (t == "uchar" || t == "uint8") return ScalarType{1, false, false};
  if (t == "short" || t == "int16") return ScalarType{2, true, false};
  if (t == "ushort" || t == "uint16") return ScalarType{2, false, false};
  if (t == "int" || t == "int32") return ScalarType{4, true, false};
  if (t == "uint" || t == "uint32") return ScalarType{4, false, false};
  if (t == "float" || t == "float32") return ScalarType{4, true, true};
  if (t == "double" || t == "float64") return ScalarType{8, true, true};
  return std::nullopt;
}

struct Property {
  ScalarType item;                   ///< a scalar, or a list's items
  std::optional<ScalarType> count;   ///< a list's count; none for a scalar
  std::string line;                  ///< its header line, rewritten with single spaces
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
  /// Whether assimp 5.2 reads it: it takes any other name's first digits for its count (none:
  /// 0 records) and returns early from `TextureFile`, reading later elements out of step.
  bool kept() const { return name == "vertex" || name == "face" || name == "tristrips" || name == "edge" || name == "material"; }
};

/// A colour value of type `t` in [0, 1] as PLY writers mean it: an integer over its type's
/// largest value (255 for uchar), a real as it is.
double colour_scale(double value, const ScalarType& t) {
  if (t.is_real) return value;
  const double largest = t.is_signed ? std::ldexp(1.0, 8 * static_cast<int>(t.bytes) - 1) - 1 : std::ldexp(1.0, 8 * static_cast<int>(t.bytes)) - 1;
  return value / largest;
}

/// A binary scalar of type `t` at bytes[pos], in the file's byte order.
double binary_scalar(const std::string& bytes, size_t pos, const ScalarType& t, bool big) {
  uint64_t raw = 0;
  for (size_t k = 0; k < t.bytes; ++k) raw = (raw << 8) | static_cast<unsigned char>(bytes[pos + (big ? k : t.bytes - 1 - k)]);
  if (t.is_real) {
    if (t.bytes == 4) {
      float f;
      const uint32_t r32 = static_cast<uint32_t>(raw);
      std::memcpy(&f, &r32, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &raw, 8);
    return d;
  }
  if (t.is_signed && t.bytes < 8 && (raw >> (8 * t.bytes - 1)) != 0) return static_cast<double>(static_cast<int64_t>(raw - (uint64_t{1} << (8 * t.bytes))));
  return static_cast<double>(raw);
}

/// The indices of the face element's scalar colour properties (red, green, blue, or
/// diffuse_red...), or none.
std::optional<std::array<size_t, 3>> face_colour_properties(const Element& e) {
  if (e.name != "face") return std::nullopt;
  std::array<size_t, 3> out{};
  const char* channels[3] = {"red", "green", "blue"};
  for (int c = 0; c < 3; ++c) {
    bool found = false;
    for (size_t k = 0; k < e.properties.size() && !found; ++k) {
      const Property& p = e.properties[k];
      const std::string name = p.line.substr(p.line.rfind(' ') + 1);
      if (!p.count && (name == channels[c] || name == std::string("diffuse_") + channels[c])) out[static_cast<size_t>(c)] = k, found = true;
    }
    if (!found) return std::nullopt;
  }
  return out;
}

/// The integer an ASCII token spells in type `t` (decimal; a sign only for a signed type, as
/// assimp reads an unsigned '+1' as 0), or none if it is not one or is out of the type's range.
std::optional<long long> integer_of(std::string_view token, const ScalarType& t) {
  // A digit first, after one sign of a signed type (assimp reads '+-1' and an unsigned '-0' as
  // 0 without moving on).
  const size_t first_digit = t.is_signed && !token.empty() && (token[0] == '-' || token[0] == '+') ? 1 : 0;
  if (token.size() <= first_digit || !std::isdigit(static_cast<unsigned char>(token[first_digit]))) return std::nullopt;
  if (token[0] == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  const int bits = static_cast<int>(8 * t.bytes);
  const long long lo = t.is_signed ? -(1LL << (bits - 1)) : 0;
  const long long hi = t.is_signed ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
  if (value < lo || value > hi) return std::nullopt;
  return value;
}

/// The finite real number an ASCII token spells: decimal, an optional sign, fraction and exponent;
/// none if it is not one or is beyond a double's range (inf and nan are refused here, as every
/// coordinate and colour must be finite).
std::optional<double> real_of(std::string_view token) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  size_t i = token.empty() || token[0] != '-' ? 0 : 1, digits = 0;
  const auto run = [&] {
    size_t n = 0;
    while (i < token.size() && std::isdigit(static_cast<unsigned char>(token[i]))) ++i, ++n;
    return n;
  };
  digits += run();
  if (i < token.size() && token[i] == '.') ++i, digits += run();
  if (digits == 0) return std::nullopt;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    if (run() == 0) return std::nullopt;
  }
  if (i != token.size()) return std::nullopt;
  double value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// A value as the canonical copy writes it, and a space: a decimal integer, or a real in its
/// shortest form that reads back to the same double (32 characters hold either).
template <typename Number>
void append_value(std::string& out, Number value) {
  char text[32];
  out.append(text, std::to_chars(text, text + sizeof text, value).ptr);
  out += ' ';
}

}  // namespace

CheckedPly check_ply(const std::string& path) {
  const std::string bytes = read_text_file(path, "mesh file");
  const auto bad = [&](const std::string& what) { return UserError(path, what); };
  // Every header and ASCII data line is text: assimp's reader ends a line at '\0', '\r' and '\f'
  // too, and a line it splits where this check does not would put a value where a list count
  // belongs (the fuzzers found it allocating for a count of 4 billion that way).
  const auto check_text = [&](std::string_view line, size_t line_no) {
    for (const char c : line)
      if (c != '\t' && (c < 0x20 || c > 0x7e)) {
        std::ostringstream byte;
        byte << "0x" << std::hex << static_cast<int>(static_cast<unsigned char>(c));
        throw bad("line " + std::to_string(line_no) + ": byte " + byte.str() +
                  " is not text (a PLY header and ASCII data are printable ASCII)");
      }
  };
  size_t pos = 0, line_no = 0;
  // The next line without its '\n' (or '\r\n'); `last` tells whether the file ends with it.
  const auto next_line = [&](bool* last) {
    const size_t end = bytes.find('\n', pos);
    *last = end == std::string::npos;
    std::string_view line(bytes.data() + pos, (*last ? bytes.size() : end) - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = *last ? bytes.size() : end + 1;
    check_text(line, ++line_no);
    return line;
  };
  const auto header_line = [&]() {
    bool last = false;
    const std::string_view line = next_line(&last);
    if (last) throw bad("PLY header has no end_header line");
    return std::string(line);
  };
  if (header_line() != "ply") throw bad("not a PLY file (its first line is not 'ply')");
  // The header is read as strictly as the format's definition says.
  std::string format;
  std::vector<Element> elements;
  const auto words_of = [](const std::string& line) {
    std::vector<std::string> words;
    std::istringstream in(line);
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  };
  // Element names are identifiers. (Property names are any word: custom attributes use '-',
  // '.' and ':'.)
  const auto is_name = [](const std::string& word) {
    return !word.empty() && (std::isalpha(static_cast<unsigned char>(word[0])) || word[0] == '_') &&
           std::all_of(word.begin(), word.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  };
  const auto count_of = [](const std::string& word) -> std::optional<size_t> {
    if (word.empty() || word.size() > 18 || word.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    return static_cast<size_t>(std::stoull(word));
  };
  for (std::string line = header_line(); line != "end_header"; line = header_line()) {
    const std::vector<std::string> words = words_of(line);
    const std::string where = "PLY header line " + std::to_string(line_no) + ": ";
    const std::string word = words.empty() ? "" : words[0];
    if (word == "format") {
      if (line_no != 2) throw bad(where + "the format line must be the second line");
      if (words.size() != 3 || words[2] != "1.0") throw bad(where + "malformed format line (expected 'format TYPE 1.0')");
      format = words[1];
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        throw bad(where + "unknown format '" + format + "'");
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
        p.count = scalar_type(words[2]);
        const std::optional<ScalarType> item = scalar_type(words[3]);
        if (!p.count || !item) throw bad(where + "unknown list types '" + words[2] + " " + words[3] + "'");
        if (p.count->is_real) throw bad(where + "a list's count type must be an integer type, not '" + words[2] + "'");
        p.item = *item;
      } else {
        if (words.size() != 3) throw bad(where + "malformed property line (expected 'property TYPE NAME')");
        const std::optional<ScalarType> type = scalar_type(words[1]);
        if (!type) throw bad(where + "unknown property type '" + words[1] + "'");
        p.item = *type;
      }
      for (const std::string& w : words) p.line += (p.line.empty() ? "" : " ") + w;
      elements.back().properties.push_back(p);
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw bad(where + "unknown keyword '" + word + "'");
    }
  }
  if (format.empty()) throw bad("PLY header has no format line (line 2: 'format ascii 1.0' or 'format binary_little_endian 1.0')");
  // A record of no properties takes no bytes, so nothing in the file would bound their number.
  for (const Element& e : elements)
    if (e.count > 0 && e.properties.empty())
      throw bad("PLY header: element '" + e.name + "' declares " + std::to_string(e.count) + " records but no properties");

  CheckedPly out;
  for (const Element& e : elements)
    if (e.name == "face") out.faces += e.count;
  // The canonical header. A binary one ends in "\r\n": after a bare '\n', assimp 5.2 takes a
  // first data byte of 0x0A for the '\n' of a "\r\n" and drops it.
  const bool binary = format != "ascii";
  out.bytes = "ply\nformat " + format + " 1.0\n";
  for (const Element& e : elements) {
    if (!e.kept()) continue;
    out.bytes += "element " + e.name + " " + std::to_string(e.count) + "\n";
    for (const Property& p : e.properties) out.bytes += p.line + "\n";
  }
  out.bytes += binary ? "end_header\r\n" : "end_header\n";

  // What the header declares, for a message: "8 vertex, 6 face".
  const auto declared = [&]() {
    std::string text;
    for (const Element& e : elements) text += (text.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
    return text;
  };
  const auto truncated = [&](const Element& e, size_t record) {
    return bad("truncated: the data ends " + (binary ? std::string() : "at line " + std::to_string(line_no + 1) + " ") + "in " +
               e.name + " " + std::to_string(record) + " of the " + std::to_string(e.count) + " its header declares");
  };
  if (!binary) {
    // One record a line, each value a number of its property's type, written anew.
    std::vector<std::string_view> tokens;
    for (const Element& e : elements) {
      const std::optional<std::array<size_t, 3>> colours = face_colour_properties(e);
      for (size_t r = 0; r < e.count; ++r) {
        if (pos == bytes.size()) throw truncated(e, r);
        bool last = false;
        const std::string_view line = next_line(&last);
        const std::string where = "line " + std::to_string(line_no) + " (" + e.name + " " + std::to_string(r) + "): ";
        tokens.clear();
        for (size_t i = 0; i < line.size();) {
          const size_t start = line.find_first_not_of(" \t", i);
          if (start == std::string_view::npos) break;
          const size_t end = std::min(line.find_first_of(" \t", start), line.size());
          tokens.push_back(line.substr(start, end - start));
          i = end;
        }
        size_t t = 0;
        const auto next_token = [&]() {
          if (t < tokens.size()) return tokens[t++];
          if (last) throw truncated(e, r);
          throw bad(where + "has fewer values than its properties take");
        };
        const auto quoted = [](std::string_view token) {
          return "'" + std::string(token.substr(0, 24)) + (token.size() > 24 ? "...'" : "'");
        };
        const size_t record_start = out.bytes.size();
        Rgb colour = Rgb::Zero();
        for (size_t pk = 0; pk < e.properties.size(); ++pk) {
          const Property& p = e.properties[pk];
          long long items = 1;
          if (p.count) {
            const std::string_view token = next_token();
            const std::optional<long long> n = integer_of(token, *p.count);
            if (!n || *n < 0) throw bad(where + "list count " + quoted(token) + " is not a count of its type");
            items = *n;
            append_value(out.bytes, *n);
          }
          for (long long k = 0; k < items; ++k) {
            const std::string_view token = next_token();
            double read = 0;
            if (p.item.is_real) {
              const std::optional<double> value = real_of(token);
              if (!value) throw bad(where + quoted(token) + " is not a finite number");
              append_value(out.bytes, *value);
              read = *value;
            } else {
              const std::optional<long long> value = integer_of(token, p.item);
              if (!value) throw bad(where + quoted(token) + " is not an integer of its property's type");
              append_value(out.bytes, *value);
              read = static_cast<double>(*value);
            }
            if (colours)
              for (int c = 0; c < 3; ++c)
                if ((*colours)[static_cast<size_t>(c)] == pk) colour[c] = colour_scale(read, p.item);
          }
        }
        if (colours) out.face_colours.push_back(colour);
        if (t != tokens.size()) throw bad(where + "has more values than its properties take");
        if (!e.kept()) {
          out.bytes.resize(record_start);
        } else {
          out.bytes.back() = '\n';  // every record has a value: an element of no properties has none
        }
      }
    }
    // Records past those the header declares: a header out of step with its data.
    while (pos < bytes.size()) {
      bool last = false;
      const std::string_view line = next_line(&last);
      if (line.find_first_not_of(" \t") != std::string_view::npos)
        throw bad("line " + std::to_string(line_no) + ": data after the last record its header declares (" + declared() + ")");
    }
    return out;
  }
  const bool big = format == "binary_big_endian";
  for (const Element& e : elements) {
    const std::optional<std::array<size_t, 3>> colours = face_colour_properties(e);
    for (size_t r = 0; r < e.count; ++r) {
      const size_t record_start = pos;
      Rgb colour = Rgb::Zero();
      for (size_t pk = 0; pk < e.properties.size(); ++pk) {
        const Property& p = e.properties[pk];
        if (!p.count) {
          if (bytes.size() - pos < p.item.bytes) throw truncated(e, r);
          if (colours)
            for (int c = 0; c < 3; ++c)
              if ((*colours)[static_cast<size_t>(c)] == pk) {
                const double value = binary_scalar(bytes, pos, p.item, big);
                if (!std::isfinite(value)) throw bad("face " + std::to_string(r) + ": its colour is not finite");
                colour[c] = colour_scale(value, p.item);
              }
          pos += p.item.bytes;
          continue;
        }
        const size_t count_bytes = p.count->bytes;
        if (bytes.size() - pos < count_bytes) throw truncated(e, r);
        uint64_t n = 0;
        for (size_t k = 0; k < count_bytes; ++k) {
          const size_t at = big ? k : count_bytes - 1 - k;
          n = (n << 8) | static_cast<unsigned char>(bytes[pos + at]);
        }
        // assimp reads a signed count as its type and then as unsigned: -1 becomes 2^32 - 1.
        if (p.count->is_signed && (n >> (8 * count_bytes - 1)) != 0)
          throw bad("malformed: " + e.name + " " + std::to_string(r) + " has a negative list count");
        pos += count_bytes;
        if (n > (bytes.size() - pos) / p.item.bytes) throw truncated(e, r);
        pos += n * p.item.bytes;
      }
      if (e.kept()) out.bytes.append(bytes, record_start, pos - record_start);
      if (colours) out.face_colours.push_back(colour);
    }
  }
  // Bytes past the records the header declares, other than line ends and blanks: a header out of
  // step with its data.
  if (bytes.find_first_not_of(" \t\r\n", pos) != std::string::npos)
    throw bad(std::to_string(bytes.size() - pos) + " bytes after the last record its header declares (" + declared() + ")");
  return out;
}

}  // namespace radrecon
