#include "io/json_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_set>
#include <vector>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"

namespace radrecon {

std::string read_text_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw UserError(path, "is a folder, not a " + what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path, "cannot open " + what + ": " + std::strerror(errno));
  check_input_file_size(path);
  std::string text;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) text.reserve(static_cast<size_t>(size));
  std::vector<char> chunk(size_t{1} << 16);  // reads pipes too, within the file-size limit
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<size_t>(in.gcount()));
    check_limit(Limit::file_bytes, static_cast<long long>(text.size()), path, "the input holds at least");
  }
  if (in.bad()) throw UserError(path, "cannot read " + what);
  return text;
}

void require_regular_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw UserError(path, "is a folder, not a " + what);
  if (std::filesystem::is_regular_file(path, ec)) {
    if (std::ifstream(path, std::ios::binary)) return;
    throw UserError(path, "cannot open " + what + ": " + std::strerror(errno));
  }
  if (std::filesystem::exists(path, ec)) throw UserError(path, "is not a regular file (a pipe or a device), not a " + what);
  throw UserError(path, "cannot open " + what + ": " + (ec ? ec.message() : std::string(std::strerror(ENOENT))));
}

namespace {

/// The 1-based line of byte `offset` of `text`.
size_t line_of(const std::string& text, size_t offset) {
  size_t line = 1;
  for (size_t i = 0; i < std::min(offset, text.size()); ++i) line += text[i] == '\n';
  return line;
}

/// A SAX handler that builds nothing and keeps the byte offset of the first error: nlohmann's
/// out_of_range exception (a number too large for a double) carries no position, its SAX
/// interface does.
class ErrorOffset final : public nlohmann::json_sax<nlohmann::json> {
 public:
  size_t offset = 0;
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception&) override {
    offset = position;
    return false;
  }
};

/// A SAX handler that builds nothing and finds the first key given twice in one object, with
/// the path of that object ("surfaces[0]"). Each open object's keys in a set (frames reused from
/// object to object).
class RepeatedKey final : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::string repeated;  ///< the key, empty if none
  std::string path;      ///< of the object holding it, "" at the top level
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    value();
    open(false).keys.clear();
    return true;
  }
  bool key(string_t& key) override {
    Frame& f = frames_[depth_ - 1];
    if (!f.keys.insert(key).second) {
      repeated = key;
      for (size_t d = 0; d + 1 < depth_; ++d)
        path += frames_[d].array ? "[" + std::to_string(frames_[d].index - 1) + "]" : (path.empty() ? "" : ".") + frames_[d].last;
      return false;  // stop here
    }
    f.last = key;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override {
    value();
    open(true).index = 0;
    return true;
  }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;                      ///< an array's values so far
    std::unordered_set<std::string> keys;  ///< an object's keys so far
    std::string last;                      ///< and the last of them, for paths
  };
  /// A value begins: an array holding it counts it.
  bool value() {
    if (depth_ > 0 && frames_[depth_ - 1].array) ++frames_[depth_ - 1].index;
    return true;
  }
  /// A new innermost frame (storage reused), its kind set.
  Frame& open(bool array) {
    if (frames_.size() <= depth_) frames_.resize(depth_ + 1);
    Frame& f = frames_[depth_++];
    f.array = array;
    return f;
  }
  bool close() {
    --depth_;
    return true;
  }
  std::vector<Frame> frames_;  ///< [0, depth_) open; beyond, kept for their storage
  size_t depth_ = 0;
};

/// The byte offset at which `text` nests arrays and objects deeper than `most` levels, if it does
/// (brackets inside strings aside).
std::optional<size_t> too_deep(const std::string& text, int most) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character, whatever it is
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > most) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::nullopt;
}

}  // namespace

JsonReader::json JsonReader::parse(const std::string& text, const std::string& kind, Keys keys) const {
  if (const std::optional<size_t> at = too_deep(text, kMaxJsonDepth))
    throw UserError(source_ + ":" + std::to_string(line_of(text, *at)),
                    "not a valid " + kind + ": nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  try {
    json doc = json::parse(text);
    if (keys == Keys::as_parsed) return doc;
    // A key given twice in one object: the document keeps the last value silently. Looked for
    // by a second pass through the SAX interface (nlohmann's parser callback, which could see
    // it in the first, made a 34 MB solution read 8 times slower).
    RepeatedKey sax;
    json::sax_parse(text, &sax);
    if (!sax.repeated.empty())
      throw UserError(source_, "not a valid " + kind + ": the key " + in_quotes(sax.repeated) + " appears twice in " +
                                   (sax.path.empty() ? std::string("the top-level object") : sax.path) +
                                   " (its last value would be taken silently)");
    return doc;
  } catch (const json::out_of_range& e) {  // a number too large for a double, e.g. 1e999
    // Parse again without a document (only on this error path) for the number's line, and keep
    // nlohmann's reason without its "[json.exception.out_of_range.406] " tag.
    ErrorOffset sax;
    json::sax_parse(text, &sax);
    std::string what = e.what();
    if (const size_t tag_end = what.find("] "); what.starts_with("[json.exception") && tag_end != std::string::npos)
      what = what.substr(tag_end + 2);
    throw UserError(source_ + ":" + std::to_string(line_of(text, sax.offset)), "not a valid " + kind + ": " + what);
  } catch (const json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line number.
    const size_t line = line_of(text, e.byte);
    // nlohmann's text starts "[json.exception.parse_error.101] parse error at line L, column C: ";
    // keep what follows "parse error" (the position and the reason).
    std::string what = e.what();
    if (const size_t at = what.find("parse error"); at != std::string::npos) what = what.substr(at);
    throw UserError(source_ + ":" + std::to_string(line), "not valid JSON: " + what);
  }
}

std::string JsonReader::join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string JsonReader::at(const std::string& path, size_t index) { return path + "[" + std::to_string(index) + "]"; }

void JsonReader::fail(const std::string& field, const std::string& what) const {
  throw UserError(source_ + ": " + field, what);
}

const JsonReader::json& JsonReader::member(const json& obj, const std::string& key, const std::string& path) const {
  if (!obj.is_object()) fail(path.empty() ? "(top level)" : path, "must be an object");
  const auto it = obj.find(key);
  if (it == obj.end()) fail(join(path, key), "missing");
  return *it;
}

double JsonReader::number(const json& j, const std::string& path) const {
  if (!j.is_number()) fail(path, "must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(path, "must be finite");
  return v;
}

std::string JsonReader::string(const json& j, const std::string& path) const {
  if (!j.is_string()) fail(path, "must be a string");
  return j.get<std::string>();
}

bool JsonReader::boolean(const json& j, const std::string& path) const {
  if (!j.is_boolean()) fail(path, "must be true or false");
  return j.get<bool>();
}

Vec3 JsonReader::vec3(const json& j, const std::string& path) const {
  if (!j.is_array() || j.size() != 3) fail(path, "must be an array of 3 numbers");
  return Vec3(number(j[0], at(path, 0)), number(j[1], at(path, 1)), number(j[2], at(path, 2)));
}

Rgb JsonReader::colour(const json& j, const std::string& path) const {
  if (j.is_number()) return Rgb::Constant(number(j, path));
  if (!j.is_array() || j.size() != 3) fail(path, "must be a number or an array [r, g, b]");
  return Rgb(number(j[0], at(path, 0)), number(j[1], at(path, 1)), number(j[2], at(path, 2)));
}

void JsonReader::no_unknown_keys(const json& obj, std::initializer_list<const char*> known,
                                 const std::string& path) const {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok) fail(join(path, it.key()), "unknown field");
  }
}

}  // namespace radrecon
