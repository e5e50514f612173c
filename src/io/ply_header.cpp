#include "io/ply_header.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
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
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> properties;
};

/// The integer an ASCII token spells in type `t` (decimal; a sign only for a signed type, as
/// assimp reads an unsigned '+1' as 0), or none if it is not one or is out of the type's range.
std::optional<long long> integer_of(std::string_view token, const ScalarType& t) {
  if (t.is_signed && !token.empty() && token[0] == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  const int bits = static_cast<int>(8 * t.bytes);
  const long long lo = t.is_signed ? -(1LL << (bits - 1)) : 0;
  const long long hi = t.is_signed ? (1LL << (bits - 1)) - 1 : (1LL << bits) - 1;
  if (value < lo || value > hi) return std::nullopt;
  return value;
}

/// Whether an ASCII token is a real number: decimal with an optional fraction and exponent, or
/// inf / infinity / nan (which the mesh's validation then refuses by name).
bool is_real(std::string_view token) {
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) token.remove_prefix(1);
  std::string lower(token);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "inf" || lower == "infinity" || lower == "nan") return true;
  size_t i = 0, digits = 0;
  const auto run = [&] {
    size_t n = 0;
    while (i < token.size() && std::isdigit(static_cast<unsigned char>(token[i]))) ++i, ++n;
    return n;
  };
  digits += run();
  if (i < token.size() && token[i] == '.') ++i, digits += run();
  if (digits == 0) return false;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    if (run() == 0) return false;
  }
  return i == token.size();
}

}  // namespace

size_t check_ply_size(const std::string& path) {
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
        throw bad("line " + std::to_string(line_no) + ": byte " + byte.str() + " is not text (a PLY header and ASCII data are printable ASCII)");
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
  for (std::string line = header_line(); line != "end_header"; line = header_line()) {
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
      elements.back().properties.push_back(p);
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      throw bad(where + "unknown keyword '" + word + "'");
    }
  }
  if (format.empty()) throw bad("PLY header has no format line");
  if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
    throw bad("PLY header: unknown format '" + format + "'");
  // A record of no properties takes no bytes, so nothing in the file would bound their number.
  for (const Element& e : elements)
    if (e.count > 0 && e.properties.empty())
      throw bad("PLY header: element '" + e.name + "' declares " + std::to_string(e.count) + " records but no properties");
  size_t faces = 0;
  for (const Element& e : elements)
    if (e.name == "face") faces += e.count;
  const auto truncated = [&](const Element& e, size_t record) {
    return bad("truncated: the data ends in " + e.name + " " + std::to_string(record) + " of the " +
               std::to_string(e.count) + " its header declares");
  };
  if (format == "ascii") {
    // One record a line, each value a number of its property's type (assimp reads it so).
    std::vector<std::string_view> tokens;
    for (const Element& e : elements)
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
        for (const Property& p : e.properties) {
          long long items = 1;
          if (p.count) {
            const std::string_view token = next_token();
            const std::optional<long long> n = integer_of(token, *p.count);
            if (!n || *n < 0) throw bad(where + "list count " + quoted(token) + " is not a count of its type");
            items = *n;
          }
          for (long long k = 0; k < items; ++k) {
            const std::string_view token = next_token();
            if (p.item.is_real ? !is_real(token) : !integer_of(token, p.item))
              throw bad(where + quoted(token) + " is not " + (p.item.is_real ? "a number" : "an integer of its property's type"));
          }
        }
        if (t != tokens.size()) throw bad(where + "has more values than its properties take");
      }
    return faces;
  }
  const bool big = format == "binary_big_endian";
  for (const Element& e : elements)
    for (size_t r = 0; r < e.count; ++r)
      for (const Property& p : e.properties) {
        if (!p.count) {
          if (bytes.size() - pos < p.item.bytes) throw truncated(e, r);
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
  return faces;
}

}  // namespace radrecon
